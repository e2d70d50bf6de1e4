using System.Globalization;
using System.Text.RegularExpressions;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.FrontDoor;

/// <summary>
/// README, "Using the outputs from Python": its second snippet (OpenEXR bindings and Spectral Python) runs as written,
/// after the first (NumPy), on a real render, with the libraries users install: Debian 12 has no python3-openexr, so a
/// venv is made offline from ../shared/anchors/wheels (openexr, spectral, numpy) unless a python3 already imports them.
/// What it reads is checked against our own readers: the EXR's X, Y, Z planes, its band channels in wavelength order,
/// and the ENVI cube and band centres against spectral.npy and wavelengths.csv.
/// </summary>
public class ReadmeExrSnippetTests
{
    static readonly string[] Modules = ["OpenEXR", "spectral", "numpy"];

    static string? Python(string work, out string reason)
    {
        var candidates = new[] { Environment.GetEnvironmentVariable("SPECTRAL_ANCHORS_PYTHON"), "/usr/bin/python3",
            Imaging.Tool.Find("python3") }
            .Where(p => p is not null && File.Exists(p)).Distinct().ToList();
        foreach (var python in candidates)
            if (Repo.Run(python!, ["-c", "import " + string.Join(", ", Modules)]).Exit == 0) { reason = ""; return python; }
        var wheels = Path.GetFullPath(Repo.PathOf("..", "shared", "anchors", "wheels"));
        var system = candidates.FirstOrDefault();
        if (system is null || !Directory.Exists(wheels))
        {
            reason = $"no python3 imports {string.Join(", ", Modules)} (Debian 12 has no python3-openexr) and {wheels} is not there";
            return null;
        }
        var venv = Path.Combine(work, "venv");
        var made = Repo.Run(system, ["-m", "venv", venv]);
        var pip = made.Exit == 0
            ? Repo.Run(Path.Combine(venv, "bin", "pip"),
                ["install", "-q", "--no-index", "--find-links", wheels, .. Modules.Select(m => m.ToLowerInvariant())])
            : made;
        reason = pip.Exit == 0 ? "" : $"could not make a venv with {string.Join(", ", Modules)} from {wheels}: {pip.Err.Trim()}";
        return pip.Exit == 0 ? Path.Combine(venv, "bin", "python") : null;
    }

    [SkippableFact]
    [Trait("Category", "Interop")]
    public void The_readme_openexr_and_spectral_python_snippet_runs_and_reads_what_we_wrote()
    {
        var work = Reference.TempDir();
        var python = Python(work, out var reason);
        Skip.If(python is null, reason);
        var readme = File.ReadAllText(Repo.PathOf("README.md"));
        var section = readme[readme.IndexOf("## Using the outputs from Python", StringComparison.Ordinal)..];
        var snippets = Regex.Matches(section, @"^```python\s*\n(.*?)^```", RegexOptions.Multiline | RegexOptions.Singleline)
            .Select(m => m.Groups[1].Value).ToList();
        Assert.Contains("OpenEXR.File", snippets[1]);

        var folder = Path.Combine(work, "out", "colorchecker");
        var (code, _, err) = CliRunner.Run("render", Repo.PathOf("scenes", "paper-3.1-colorchecker-d65.json"), "-o", folder,
            "--width", "36", "--formats", "exr,npy,envi,png", "--quiet");
        Assert.True(code == 0, err);
        File.WriteAllText(Path.Combine(work, "snippet.py"), snippets[0] + "\n" + snippets[1] + """

            print("XYZ", *(repr(float(p.mean())) for p in (X, Y, Z)))
            print("BANDS", *spectral)
            print("ENVI", *cube_envi.shape, repr(float(abs(cube_envi - cube).max())), *(repr(float(c)) for c in centres_nm))
            """);
        (code, var stdout, err) = Repo.Run(python!, ["snippet.py"], workDir: work);
        Assert.True(code == 0, $"the README snippets failed:\n{err}");
        string[] Line(string tag) => stdout.Split('\n').Single(l => l.StartsWith(tag + " ", StringComparison.Ordinal)).Split(' ')[1..];
        static double D(string s) => double.Parse(s, CultureInfo.InvariantCulture);

        var exr = ExrReader.Read(Path.Combine(folder, "spectral.exr"));
        var xyz = Line("XYZ").Select(D).ToArray();
        for (int c = 0; c < 3; c++)
        {
            double mean = exr.OtherChannels["XYZ"[c].ToString()].Select(v => (double)v).Average();
            Assert.True(Math.Abs(xyz[c] - mean) <= 1e-6 * Math.Max(1, mean), $"{"XYZ"[c]}: OpenEXR {xyz[c]:G9}, our reader {mean:G9}");
        }
        var centres = File.ReadAllLines(Path.Combine(folder, "wavelengths.csv")).Skip(1).Where(l => l.Length > 0)
            .Select(l => D(l.Split(',')[2])).ToArray();
        var bands = Line("BANDS");
        Assert.Equal(centres.Length, bands.Length);
        for (int b = 0; b < bands.Length; b++)
            Assert.True(Math.Abs(D(bands[b][3..^2].Replace(',', '.')) - centres[b]) < 0.01,
                $"band {b + 1}: {bands[b]}, centre {centres[b]} nm");
        var envi = Line("ENVI");
        var cube = NpyReader.ReadImage(Path.Combine(folder, "spectral.npy"));
        Assert.Equal([cube.Height, cube.Width, cube.Bands], envi[..3].Select(int.Parse));
        Assert.Equal(0, D(envi[3]));
        Assert.Equal(centres, envi[4..].Select(D), (a, b) => Math.Abs(a - b) < 1e-9);
    }
}
