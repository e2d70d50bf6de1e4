using SpectralRenderer.Color;
using SpectralRenderer.Imaging;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Scenes;

/// <summary>
/// The metamerism report of RGB textures (issue 26): for the 24 ColorChecker sRGB codes, the three-box metamer matches the
/// colour under D65 (ΔE00 ≤ 0.01, integrated here independently at 0.1 nm) whenever it is a reflectance, and the reported
/// spread under illuminant A and FL11 equals the ΔE00 of the two metamers integrated here under those lights (to 0.01).
/// </summary>
public class MetamerismTests(Xunit.Abstractions.ITestOutputHelper output)
{
    [Fact]
    public void The_box_metamer_matches_under_D65_and_the_spread_under_A_and_FL11_is_the_independent_one()
    {
        var uplift = new SigmoidUplift();
        var report = new UpliftMetamerism(uplift);
        var wl = SigmoidUplift.Wavelengths;
        string[] lights = ["A", "FL11"];
        var colorimeters = lights.Select(UpliftMetamerism.Under).ToArray();
        var d65White = RgbTextureTests.Integrate(wl, [.. wl.Select(_ => 1.0)]);
        int admissible = 0;
        double largest = 0;
        foreach (var (r, g, b) in RgbTextureTests.Codes())
        {
            var box = report.BoxMetamer(RgbTextureTests.Target(r, g, b), out bool ok);
            var spread = report.Spread(r, g, b, 255, colorimeters);
            Assert.Equal(ok, spread is not null);
            if (!ok) continue;
            admissible++;
            Assert.All(box, v => Assert.InRange(v, -1e-9, 1 + 1e-9));
            Assert.True(DeltaE2000.Between(Lab.FromXyz(RgbTextureTests.Integrate(wl, box), d65White),
                Lab.FromXyz(RgbTextureTests.Target(r, g, b), d65White)) <= 0.01);
            var smooth = uplift.FromSrgbCodes(r, g, b, 255);
            for (int k = 0; k < lights.Length; k++)
            {
                var white = RgbTextureTests.Integrate(wl, [.. wl.Select(_ => 1.0)], lights[k]);
                double expected = DeltaE2000.Between(Lab.FromXyz(RgbTextureTests.Integrate(wl, smooth, lights[k]), white),
                    Lab.FromXyz(RgbTextureTests.Integrate(wl, box, lights[k]), white));
                Assert.Equal(expected, spread![k], 0.01);
                largest = Math.Max(largest, spread[k]);
            }
        }
        output.WriteLine($"{admissible} of 24 codes have an admissible box metamer; largest spread under A/FL11 {largest:F2} ΔE00");
        Assert.True(admissible >= 1);
        Assert.True(largest > 0.1, "the two metamers should differ under A or FL11");
    }

    [Fact]
    public void The_command_reports_every_light()
    {
        var dir = Reference.TempDir();
        var codes = RgbTextureTests.Codes();
        var rgb = codes.SelectMany(c => new[] { (byte)c.R, (byte)c.G, (byte)c.B }).ToArray();
        var file = Path.Combine(dir, "chart.png");
        using (var f = File.Create(file)) PngWriter.WriteRgb8(f, 6, 4, rgb);
        var (exit, stdout, stderr) = CliRunner.Run("metamerism", file);
        Assert.True(exit == 0, stderr);
        foreach (var light in UpliftMetamerism.DefaultLights) Assert.Contains(light, stdout);
        output.WriteLine(stdout);
    }
}
