namespace SpectralRenderer.Tests;

/// <summary>The anchors' Python (Mitsuba 3, colour-science, NumPy) for the Interop tests, or a skip saying why not.</summary>
public static class AnchorsPython
{
    /// <summary>SPECTRAL_ANCHORS_PYTHON when it can import mitsuba, colour and numpy; else the test is skipped with the reason.</summary>
    public static string Require()
    {
        var python = Environment.GetEnvironmentVariable("SPECTRAL_ANCHORS_PYTHON");
        Skip.If(python is null || !File.Exists(python),
            "SPECTRAL_ANCHORS_PYTHON is not set to the anchors' Python (../shared/anchors/setup.sh VENV; VENV/bin/python)");
        Skip.If(Repo.Run(python!, ["-c", "import mitsuba, colour, numpy"]).Exit != 0,
            $"{python} cannot import mitsuba, colour and numpy (make it with ../shared/anchors/setup.sh)");
        return python!;
    }
}
