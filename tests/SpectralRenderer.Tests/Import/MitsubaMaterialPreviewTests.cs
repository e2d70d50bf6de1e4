using System.Globalization;

namespace SpectralRenderer.Tests.Import;

/// <summary>
/// Issue 39's material-preview bar: scenes/mitsuba-material-preview.xml — a smooth conductor, a rough GGX conductor (eta
/// and k as λ:v lists), a glass and a diffuse sphere on a grey floor under an environment map (a generated 64 × 32 PFM with a
/// small bright sun, turned by to_world) — rendered by Mitsuba 3 from the file itself and by us through the importer's
/// envmap sky (`spectral render FILE.xml`, path integrator), scripts/compare-mitsuba.py --xml as for the Cornell box
/// (MitsubaCornellImportTests): every region (the objects seen and the image's quadrants), every band, within 1 % or 3σ
/// (the issue asked 2 % with model differences stated; there are none left here). Mitsuba's scalar_spectral variant, an
/// independent renderer. 32 × 24 pixels, 40 nm bands, 8 parts × 1024 spp; the converged run is in docs/import.md. Needs the
/// anchors' Python (SPECTRAL_ANCHORS_PYTHON, AnchorsPython); skipped without it.
/// </summary>
public class MitsubaMaterialPreviewTests
{
    [SkippableFact]
    [Trait("Category", "Interop")]
    public void The_imported_material_preview_under_an_environment_map_matches_mitsuba()
    {
        var python = AnchorsPython.Require();

        var spectral = Path.Combine(AppContext.BaseDirectory, "spectral.dll");
        var (exit, stdout, stderr) = Repo.Run(python, [Repo.PathOf("scripts", "compare-mitsuba.py"),
            "--xml", Repo.PathOf("scenes", "mitsuba-material-preview.xml"), "--variant", "scalar_spectral",
            "--width", "32", "--height", "24", "--ref-spp", "8192", "--parts", "8", "--xml-bands", "380:780:10",
            "--spectral", spectral], timeoutMs: 900_000);
        Assert.True(exit == 0, $"compare-mitsuba.py failed:\n{stderr}");

        var bands = stdout.Split('\n').Where(l => l.StartsWith("BAND ", StringComparison.Ordinal)).ToList();
        Assert.True(bands.Count >= 6 * 10, $"too few region × band figures:\n{stdout}");
        foreach (var name in new[] { "gold-ball", "copper-ball", "glass-ball", "clay-ball", "floor" })
            Assert.Contains(bands, l => l.Contains($"region={name} ", StringComparison.Ordinal));
        foreach (var line in bands)
        {
            var f = line.Split(' ', StringSplitOptions.RemoveEmptyEntries).Skip(1)
                .Select(kv => kv.Split('=')).ToDictionary(kv => kv[0], kv => kv[1]);
            double rel = double.Parse(f["rel"], CultureInfo.InvariantCulture), se = double.Parse(f["se"], CultureInfo.InvariantCulture);
            Assert.True(Math.Abs(rel) <= Math.Max(0.01, 3 * se),
                $"{f["region"]} band {f["band"]}: Mitsuba/ours − 1 = {rel:P2} ± {se:P2} (bar: 1 % or 3σ)\n{stdout}");
        }
    }
}
