using System.Globalization;
using System.Text.Json.Nodes;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Imaging;
using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Sensor;

/// <summary>
/// ARCHITECTURE.md, "Extending", a sensor preset: one definition and one <see cref="SensorPresets.Register"/> call from
/// this assembly, and `spectral camera --sensor NAME` uses it without a change to the engine.
/// </summary>
public class RegisteredPresetTests
{
    /// <summary>The example preset: a camera with every channel at every pixel, one flat channel and one 500–600 nm box.</summary>
    const string Name = "test-flat-and-box";

    static SensorModel FlatAndBox() => new()
    {
        Name = Name,
        Arrangement = Arrangement.Full,
        Source = "a test preset: quantum efficiency 0.5 on 380–780 nm, and 0.5 on 500–600 nm",
        Channels =
        [
            new SensorChannel("flat", new TabulatedSpectrum("flat", [380.0, 780.0], [0.5, 0.5], Extrapolation.Zero), "0.5 on 380–780 nm"),
            new SensorChannel("box", new TabulatedSpectrum("box", [500.0, 600.0], [0.5, 0.5], Extrapolation.Zero), "0.5 on 500–600 nm"),
        ],
    };

    static RegisteredPresetTests() => SensorPresets.Register(Name, FlatAndBox);

    /// <summary>∫ E(λ)·λ dλ over [lo, hi] of the table's linear interpolant, by the midpoint rule on 0.01 nm steps (not the engine's
    /// code).</summary>
    static double LightTimesWavelength(string file, string column, double lo, double hi)
    {
        var lines = File.ReadAllLines(Path.Combine(DataDirectory.Path, file));
        int col = Array.IndexOf(lines[0].Split(','), column);
        var rows = lines.Skip(1).Where(l => l.Length > 0).Select(l => l.Split(',')).ToArray();
        var wl = rows.Select(r => double.Parse(r[0], CultureInfo.InvariantCulture)).ToArray();
        var v = rows.Select(r => double.Parse(r[col], CultureInfo.InvariantCulture)).ToArray();
        double sum = 0;
        const double h = 0.01;
        for (double x = lo + h / 2; x < hi; x += h)
        {
            int i = Math.Clamp(Array.BinarySearch(wl, x) is var k && k >= 0 ? k : ~k - 1, 0, wl.Length - 2);
            double e = v[i] + (x - wl[i]) / (wl[i + 1] - wl[i]) * (v[i + 1] - v[i]);
            sum += e * x * h;
        }
        return sum;
    }

    [Fact]
    public void A_preset_registered_from_outside_the_engine_runs_in_the_camera_command()
    {
        Assert.Contains(Name, SensorPresets.Names);
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "white.json");
        // A white (0.9) and a grey (0.3) diffuser lit head-on by D65: each band radiance is R·E_b, the light's shape.
        File.WriteAllText(scene, """
        {
          "bands": "380:780:20", "white": "D65",
          "camera": { "position": [0, 0, 10], "look_at": [0, 0, 0], "fov": 30, "width": 16, "height": 8 },
          "materials": { "white": { "diffuse": 0.9 }, "grey": { "diffuse": 0.3 } },
          "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "D65" } ],
          "objects": [
            { "type": "quad", "name": "white", "center": [-1, 0, 0], "size": 1.8, "material": "white" },
            { "type": "quad", "name": "grey", "center": [1, 0, 0], "size": 1.8, "material": "grey" }
          ]
        }
        """);
        var render = Path.Combine(dir, "out");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", render, "--quiet");
        Assert.True(code == 0, err);
        var cam = Path.Combine(render, "cam");
        (code, _, err) =
            CliRunner.Run("camera", render, "--sensor", Name, "--noise", "off", "-o", cam, "--off-axis", "none", "--psf", "none");
        Assert.True(code == 0, err);

        var manifest = JsonNode.Parse(File.ReadAllText(Path.Combine(cam, "camera.json")))!;
        Assert.Equal(Name, (string?)manifest["sensor"]!["name"]);
        var (shape, raw) = NpyReader.Read(File.OpenRead(Path.Combine(cam, "raw.npy")));
        Assert.Equal([8, 16, 2], shape);

        // Photo-electrons ∝ ∫ η(λ) L(λ) λ dλ with L ∝ E (D65) on a flat diffuser: the box channel over the flat one is
        // ∫_500^600 E λ dλ / ∫_380^780 E λ dλ, whatever the exposure, optics and gain.
        double expected =
            LightTimesWavelength("illuminants.csv", "D65", 500, 600) / LightTimesWavelength("illuminants.csv", "D65", 380, 780);
        var folder = CameraScene.Open(render).Folder;
        var signal = new Dictionary<string, double>();
        foreach (var name in new[] { "white", "grey" })
        {
            int id = folder.ObjectIndex(name);
            int pixel = Array.FindIndex(folder.ObjectIds, v => v == id);
            Assert.True(raw[pixel * 2] > 0, $"{name}: no signal");
            Assert.InRange(raw[pixel * 2 + 1] / raw[pixel * 2] / expected, 1 - 1e-5, 1 + 1e-5);
            signal[name] = raw[pixel * 2];
        }
        Assert.InRange(signal["grey"] / signal["white"], 0.3 / 0.9 * (1 - 1e-5), 0.3 / 0.9 * (1 + 1e-5));   // linear in radiance
    }

    [Fact]
    public void A_name_already_taken_is_refused()
    {
        Assert.Throws<ArgumentException>(() => SensorPresets.Register("cie-xyz", FlatAndBox));
        Assert.Throws<ArgumentException>(() => SensorPresets.Register("My Sensor", FlatAndBox));
    }
}
