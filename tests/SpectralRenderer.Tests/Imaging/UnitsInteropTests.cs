using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Imaging;

/// <summary>What a render's files say about their units, as exrheader, gdalinfo and oiiotool read them (skipped without the
/// tools).</summary>
public class UnitsInteropTests
{
    static string Require(string tool, string package)
    {
        var path = Tool.Find(tool);
        Skip.If(path is null, $"{tool} is not installed (Debian package {package}); skipping this interop test");
        return path!;
    }

    static string Render(string radiometry)
    {
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, $$"""
        { "radiometry": "{{radiometry}}", "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 16, "height": 12 },
          "materials": { "green": { "diffuse": "colorchecker:14" } },
          "lights": [ { "type": "point", "position": [0, 3, 3], "spectrum": "D65" } ],
          "objects": [ { "type": "sphere", "radius": 1, "material": "green" } ] }
        """);
        var outDir = Path.Combine(dir, "out");
        var (code, _, err) = CliRunner.Run("render", scene, "-o", outDir, "--quiet");
        Assert.True(code == 0, err);
        return outDir;
    }

    [SkippableTheory]
    [Trait("Category", "Interop")]
    [InlineData("paper")]
    [InlineData("physical")]
    public void Exrheader_shows_emissiveUnits_only_for_physical_radiometry(string radiometry)
    {
        var exe = Require("exrheader", "openexr");
        var (exit, stdout, stderr) = Tool.Run(exe, [Path.Combine(Render(radiometry), "spectral.exr")]);
        Assert.True(exit == 0, stderr);
        Assert.Equal(radiometry == "physical", stdout.Contains("emissiveUnits (type string): \"W.m^-2.sr^-1\""));
        Assert.Contains($"spectralRadiometry (type string): \"{radiometry}:", stdout);
    }

    [SkippableFact]
    [Trait("Category", "Interop")]
    public void Gdalinfo_reads_the_radiometry_and_data_units_of_the_ENVI_cube()
    {
        var exe = Require("gdalinfo", "gdal-bin");
        var (exit, stdout, stderr) = Tool.Run(exe, ["-mdd", "all", Path.Combine(Render("physical"), "spectral.img")]);
        Assert.True(exit == 0, stderr);
        Assert.Contains("radiometry=physical", stdout);
        Assert.Contains("data_units=W.m^-2.sr^-1.nm^-1", stdout);
    }

    [SkippableFact]
    [Trait("Category", "Interop")]
    public void Oiiotool_sees_a_linear_band_png_with_its_scale()
    {
        var exe = Require("oiiotool", "openimageio-tools");
        var band = Directory.GetFiles(Path.Combine(Render("physical"), "bands"), "band-01-*.png").Single();
        var (exit, stdout, stderr) = Tool.Run(exe, ["--info", "-v", band]);
        Assert.True(exit == 0, stderr);
        Assert.Contains("oiio:Gamma: 1", stdout);
        Assert.Contains("Scale: \"band value = sample / 65535 *", stdout);
        Assert.Contains("W.m^-2.sr^-1.nm^-1", stdout);
    }
}
