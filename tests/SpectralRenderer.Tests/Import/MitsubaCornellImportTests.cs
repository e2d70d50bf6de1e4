using System.Globalization;

namespace SpectralRenderer.Tests.Import;

/// <summary>
/// Issue 39's bar: a Cornell box written in Mitsuba 3 XML (scenes/mitsuba-cornell-box.xml: λ:v reflectances, a λ:v area
/// light, rotated boxes) rendered by Mitsuba 3 from the file itself and by us through the importer (`spectral render
/// FILE.xml`, path integrator): scripts/compare-mitsuba.py --xml rewrites only the film (size; Mitsuba's a specfilm of box
/// bands) and the sampler (count, seed) in a copy and prints every region's relative difference per band with its standard
/// error (8 independent parts each, 1024 spp per part). Every region (the objects seen and the image's quadrants), every
/// band: within 1 % or 3σ. Mitsuba's scalar_spectral variant, an independent renderer. Sized to run in about a minute on two
/// cores: 24 × 24 pixels and 40 nm bands, where Mitsuba's wavelength sampling leaves σ of 0.2–1.8 %; the converged run
/// (32 × 32, 20 nm bands, 8 × 4096 spp, docs/import.md) is within 1 % in all but 3 of 220 figures, those within 2σ.
/// Needs the anchors' Python (SPECTRAL_ANCHORS_PYTHON, AnchorsPython); skipped without it.
/// </summary>
public class MitsubaCornellImportTests
{
    [SkippableFact]
    [Trait("Category", "Interop")]
    public void The_imported_cornell_box_matches_mitsuba_rendering_the_same_xml() =>
        AssertMatchesMitsuba("mitsuba-cornell-box.xml", 24, 24, 8192, 8, "380:780:10", 6, 0.01);

    /// <summary>
    /// scripts/compare-mitsuba.py --xml on scenes/<paramref name="xml"/> (Mitsuba 3 scalar_spectral against ours through the
    /// importer): at least <paramref name="regions"/> regions × the bands, each within <paramref name="limit"/> (relative) or 3σ;
    /// returns the script's output.
    /// </summary>
    internal static string AssertMatchesMitsuba(string xml, int width, int height, int spp, int parts, string bandEdges, int regions,
        double limit)
    {
        var python = AnchorsPython.Require();

        var spectral = Path.Combine(AppContext.BaseDirectory, "spectral.dll");
        var (exit, stdout, stderr) = Repo.Run(python, [Repo.PathOf("scripts", "compare-mitsuba.py"),
            "--xml", Repo.PathOf("scenes", xml), "--variant", "scalar_spectral",
            "--width", $"{width}", "--height", $"{height}", "--ref-spp", $"{spp}", "--parts", $"{parts}", "--xml-bands", bandEdges,
            "--spectral", spectral], timeoutMs: 900_000);
        Assert.True(exit == 0, $"compare-mitsuba.py failed:\n{stderr}");

        var bands = stdout.Split('\n').Where(l => l.StartsWith("BAND ", StringComparison.Ordinal)).ToList();
        Assert.True(bands.Count >= regions * int.Parse(bandEdges.Split(':')[2], CultureInfo.InvariantCulture),
            $"too few region × band figures:\n{stdout}");
        foreach (var line in bands)
        {
            var f = line.Split(' ', StringSplitOptions.RemoveEmptyEntries).Skip(1)
                .Select(kv => kv.Split('=')).ToDictionary(kv => kv[0], kv => kv[1]);
            double rel = double.Parse(f["rel"], CultureInfo.InvariantCulture), se = double.Parse(f["se"], CultureInfo.InvariantCulture);
            Assert.True(Math.Abs(rel) <= Math.Max(limit, 3 * se),
                $"{f["region"]} band {f["band"]}: Mitsuba/ours − 1 = {rel:P2} ± {se:P2} (bar: {limit:P0} or 3σ)\n{stdout}");
        }
        return stdout;
    }
}
