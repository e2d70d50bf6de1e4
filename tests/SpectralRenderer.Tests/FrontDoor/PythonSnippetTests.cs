using System.Globalization;
using System.Text.RegularExpressions;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.FrontDoor;

/// <summary>
/// README, "Using the outputs from Python": its NumPy snippet runs with the system python3 on a real render; the
/// XYZ it computes from spectral.npy and render.json's weights equals eq. 3 summed here in C# over the same cube,
/// and lies within 0.5 % of the exact pixel colours the renderer wrote into spectral.exr's X Y Z (read by our EXR
/// reader) for the §3.1 chart under D65.
/// </summary>
public class PythonSnippetTests
{
    static string? PythonWithNumpy(out string reason)
    {
        // Debian's python3 first (.ci/run installs python3-numpy there), then whichever python3 is on the PATH.
        var candidates = new[] { "/usr/bin/python3", Imaging.Tool.Find("python3") }.Where(p => p is not null && File.Exists(p)).Distinct()
            .ToList();
        foreach (var python in candidates)
            if (Repo.Run(python!, ["-c", "import numpy"]).Exit == 0) { reason = ""; return python; }
        reason = candidates.Count == 0
            ? "python3 is not installed"
            : $"numpy is not importable by {string.Join(" or ", candidates)} (Debian package python3-numpy; .ci/run installs it)";
        return null;
    }

    [SkippableFact]
    [Trait("Category", "Interop")]
    public void The_readme_numpy_snippet_runs_and_its_xyz_equals_the_exr_channels()
    {
        var python = PythonWithNumpy(out var reason);
        Skip.If(python is null, reason);
        var readme = File.ReadAllText(Repo.PathOf("README.md"));
        var section = readme[readme.IndexOf("## Using the outputs from Python", StringComparison.Ordinal)..];
        var snippet = Regex.Match(section, @"^```python\s*\n(.*?)^```", RegexOptions.Multiline | RegexOptions.Singleline).Groups[1].Value;
        Assert.Contains("np.load", snippet);

        var work = Reference.TempDir();
        var scene = Repo.PathOf("scenes", "paper-3.1-colorchecker-d65.json");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", Path.Combine(work, "out", "colorchecker"), "--width", "72", "--formats",
            "exr,npy", "--quiet");
        Assert.True(code == 0, err);
        File.WriteAllText(Path.Combine(work, "snippet.py"),
            snippet + "\nprint('XYZ-MEAN', *(repr(float(v)) for v in xyz.reshape(-1, 3).mean(axis=0)))\n");
        (code, var stdout, err) = Repo.Run(python!, ["snippet.py"], workDir: work);
        Assert.True(code == 0, $"the README snippet failed:\n{err}");
        var line = stdout.Split('\n').Single(l => l.StartsWith("XYZ-MEAN ", StringComparison.Ordinal)).Split(' ')[1..];
        var fromPython = line.Select(v => double.Parse(v, CultureInfo.InvariantCulture)).ToArray();

        var folder = Path.Combine(work, "out", "colorchecker");
        var cube = NpyReader.ReadImage(Path.Combine(folder, "spectral.npy"));
        var manifest = System.Text.Json.Nodes.JsonNode.Parse(File.ReadAllText(Path.Combine(folder, "render.json")))!["colour"]!;
        var exr = ExrReader.Read(Path.Combine(folder, "spectral.exr"));
        for (int c = 0; c < 3; c++)
        {
            var w = manifest[$"weights_{"xyz"[c]}"]!.AsArray().Select(v => (double)v!).ToArray();
            double sum = 0;
            for (int y = 0; y < cube.Height; y++)
                for (int x = 0; x < cube.Width; x++)
                    for (int b = 0; b < cube.Bands; b++) sum += w[b] * cube[x, y, b];
            double mean = sum / (cube.Width * cube.Height);
            Assert.True(Math.Abs(fromPython[c] - mean) <= 1e-6 * Math.Max(1, Math.Abs(mean)),
                $"{"XYZ"[c]}: python {fromPython[c]:G9}, eq. 3 here {mean:G9}");
            double exact = exr.OtherChannels["XYZ"[c].ToString()].Select(v => (double)v).Average();
            Assert.True(Math.Abs(fromPython[c] - exact) <= 0.005 * exact,
                $"{"XYZ"[c]}: cube colour {fromPython[c]:G9}, exact pixel colour {exact:G9}");
        }
        Assert.True(fromPython[1] > 0.05, "the chart is lit");
    }
}
