using System.Globalization;
using System.Text;
using System.Text.Json.Nodes;
using SpectralRenderer.Scenes.Import;
using SpectralRenderer.Scenes.Import.Pbrt;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Import;

/// <summary>
/// pbrt-v4's named spectra through the importer: each equals pbrt-v4's table (data/pbrt-v4, extracted from
/// src/pbrt/util/spectrum.cpp at commit 5f7a606) at the table's own wavelengths to 1e-6, a few values read by eye from
/// spectrum.cpp (the line cited), and the illuminants carry pbrt's normalisation Σ ȳ·S = CIE_Y_integral.
/// </summary>
public class PbrtSpectraTests
{
    /// <summary>Every column of data/pbrt-v4/*.csv, read here with a plain split (not the engine's reader).</summary>
    static Dictionary<string, (double[] Wl, double[] V, bool Illuminant)> Tables()
    {
        var all = new Dictionary<string, (double[], double[], bool)>();
        foreach (var file in Directory.GetFiles(Repo.PathOf("data", "pbrt-v4"), "*.csv"))
        {
            var lines = File.ReadAllLines(file).Where(l => l.Length > 0).ToArray();
            var header = lines[0].Split(',');
            var rows = lines.Skip(1).Select(l => l.Split(',').Select(c => double.Parse(c, CultureInfo.InvariantCulture)).ToArray())
                .ToArray();
            for (int c = 1; c < header.Length; c++)
                all[header[c]] = (rows.Select(r => r[0]).ToArray(), rows.Select(r => r[c]).ToArray(),
                    Path.GetFileName(file).StartsWith("illuminants", StringComparison.Ordinal));
        }
        return all;
    }

    /// <summary>A pbrt scene using every named spectrum: metals as conductors, glasses as dielectrics, illuminants as lights.</summary>
    static string SceneUsingAll(IEnumerable<string> names)
    {
        var sb = new StringBuilder("LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 4 "
            + "\"integer yresolution\" 4\nWorldBegin\n");
        int i = 0;
        foreach (var name in names)
        {
            i++;
            if (name.StartsWith("metal-", StringComparison.Ordinal) && name.EndsWith("-eta", StringComparison.Ordinal))
                sb.Append($"AttributeBegin\nMaterial \"conductor\" \"spectrum eta\" \"{name}\" \"spectrum k\" \"{name[..^4]}-k\"\n"
                    + $"Translate {i} 0 0\nShape \"sphere\" \"float radius\" 0.1\nAttributeEnd\n");
            else if (name.StartsWith("glass-", StringComparison.Ordinal))
                sb.Append($"AttributeBegin\nMaterial \"dielectric\" \"spectrum eta\" \"{name}\"\nTranslate {i} 1 0\n"
                    + "Shape \"sphere\" \"float radius\" 0.1\nAttributeEnd\n");
            else if (!name.StartsWith("metal-", StringComparison.Ordinal))
                sb.Append($"LightSource \"point\" \"spectrum I\" \"{name}\" \"point3 from\" [ {i} 3 0 ]\n");
        }
        return sb.ToString();
    }

    [Fact]
    public void Every_named_spectrum_equals_pbrts_table_and_the_scene_loads()
    {
        var tables = Tables();
        Assert.Equal(7 + 7 * 2 + 16, tables.Count);   // 7 glasses, 7 metals' n and k, 16 illuminants
        var path = Repo.PathOf("scenes", "pbrt", "all-named.pbrt");
        var imported = new PbrtConverter(path, new ImportOptions()).ConvertText(SceneUsingAll(tables.Keys.Order(StringComparer.Ordinal)));
        var spectra = imported.Scene["spectra"]!.AsObject();
        foreach (var (name, (wl, v, illuminant)) in tables)
        {
            var entry = spectra[name]?.AsObject();
            Assert.True(entry is not null, $"{name} was not resolved");
            var pairs = entry!["values"]!.AsArray();
            Assert.Equal(wl.Length, pairs.Count);
            for (int i = 0; i < wl.Length; i++)
            {
                Assert.True(Math.Abs(pairs[i]![0]!.GetValue<double>() - wl[i]) <= 1e-6, $"{name} wavelength {i}");
                Assert.True(Math.Abs(pairs[i]![1]!.GetValue<double>() - v[i]) <= 1e-6, $"{name} at {wl[i]} nm");
            }
            Assert.Equal("clamp", entry["extrapolate"]!.GetValue<string>());   // FromInterleaved holds the end values
            Assert.Equal(illuminant, entry["scale"] is not null);
        }
        var scene = SceneLoader.Parse(ImportWriter.InlineJson(imported), path);
        Assert.True(scene.Materials.Count >= 14);
    }

    [Theory]
    // spectrum.cpp (pbrt-v4 5f7a606) line 1211–1212: Au_eta … 551.040771, 0.345500
    [InlineData("metal-Au-eta", 551.040771, 0.3455)]
    // line 1220: Au_k begins 298.757050, 1.920375
    [InlineData("metal-Au-k", 298.757050, 1.920375)]
    // line 1356: GlassBK7_eta … 586, 1.516865556749
    [InlineData("glass-BK7", 586, 1.516865556749)]
    // line 770: CIE_Illum_D6500 … 360.000000, 46.638302
    [InlineData("stdillum-D65", 360, 46.638302)]
    public void Values_read_by_eye_from_spectrum_cpp(string name, double nm, double value)
    {
        Assert.True(PbrtNamedSpectra.TryGet(name, out var table, out _));
        Assert.Equal(value, table.Evaluate(nm), 1e-9);
    }

    [Fact]
    public void An_illuminant_is_scaled_as_pbrt_normalises_it_to_CIE_Y_integral()
    {
        // Σ over λ = 360…830 of ȳ(λ)·scale·S(λ) = 106.856895 (pbrt-v4 spectrum.h CIE_Y_integral), ȳ from the CMF CSV read here.
        var cmf = File.ReadAllLines(Repo.PathOf("data", "cie1931-2deg-cmf.csv")).Skip(1).Where(l => l.Length > 0)
            .Select(l => l.Split(',')).ToDictionary(c => (int)double.Parse(c[0], CultureInfo.InvariantCulture),
                c => double.Parse(c[2], CultureInfo.InvariantCulture));
        var tables = Tables();
        foreach (var name in new[] { "stdillum-A", "stdillum-D65", "stdillum-F11", "illum-acesD60" })
        {
            var (wl, v, _) = tables[name];
            double scale = PbrtNamedSpectra.Normalisation(name), sum = 0;
            for (int l = 360; l <= 830; l++)
            {
                int k = Math.Clamp(Array.FindLastIndex(wl, w => w <= l), 0, wl.Length - 2);
                double s = l <= wl[0] ? v[0] : l >= wl[^1] ? v[^1] : v[k] + (l - wl[k]) / (wl[k + 1] - wl[k]) * (v[k + 1] - v[k]);
                sum += cmf[l] * scale * s;
            }
            Assert.Equal(106.856895, sum, 1e-6);
        }
    }

    [Fact]
    public void Glass_BK7_is_the_dispersive_index_of_pbrts_table_at_each_band_centre()
    {
        var path = Repo.PathOf("scenes", "pbrt", "bk7.pbrt");
        var imported = new PbrtConverter(path, new ImportOptions()).ConvertText("LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\n"
            + "WorldBegin\nMaterial \"dielectric\" \"spectrum eta\" \"glass-BK7\"\nShape \"sphere\"");
        var scene = SceneLoader.Parse(ImportWriter.InlineJson(imported), path);
        var glass = scene.Materials.Single(m => m.Dispersive);
        var (wl, v, _) = Tables()["glass-BK7"];
        for (int b = 0; b < scene.Bands; b++)
        {
            double centre = scene.Grid.Centre(b);
            int k = Array.FindLastIndex(wl, w => w <= centre);
            double n = v[k] + (centre - wl[k]) / (wl[k + 1] - wl[k]) * (v[k + 1] - v[k]);
            Assert.Equal((float)n, glass.Ior[b]);
        }
    }
}
