namespace SpectralRenderer.Tests.Import;

/// <summary>
/// Issue 39's material-preview bar: scenes/mitsuba-material-preview.xml — a smooth conductor, a rough GGX conductor (eta
/// and k as λ:v lists), a glass and a diffuse sphere on a grey floor under an environment map (a generated 64 × 32 PFM with a
/// small bright sun, turned by to_world) — rendered by Mitsuba 3 from the file itself and by us through the importer's
/// envmap sky (`spectral render FILE.xml`, path integrator), scripts/compare-mitsuba.py --xml as for the Cornell box
/// (MitsubaCornellImportTests): every region (the objects seen and the image's quadrants), every band, within the issue's
/// 2 % or 3σ. The Cornell box's 1 % is not met here: Mitsuba renders 0.2–0.6 % lower over the bands in most regions, up to
/// 1.2 % in the upper right quadrant (the far floor's edge against the sky, the glass ball), a cause not found yet
/// (docs/import.md). Mitsuba's scalar_spectral variant, an
/// independent renderer. 32 × 24 pixels, 40 nm bands, 8 parts × 1024 spp; the converged run is in docs/import.md. Needs the
/// anchors' Python (SPECTRAL_ANCHORS_PYTHON, AnchorsPython); skipped without it.
/// </summary>
public class MitsubaMaterialPreviewTests
{
    [SkippableFact]
    [Trait("Category", "Interop")]
    public void The_imported_material_preview_under_an_environment_map_matches_mitsuba()
    {
        var stdout = MitsubaCornellImportTests.AssertMatchesMitsuba("mitsuba-material-preview.xml", 32, 24, 8192, 8, "380:780:10", 6,
            0.02);
        foreach (var name in new[] { "gold-ball", "copper-ball", "glass-ball", "clay-ball", "floor" })
            Assert.Contains($"BAND region={name} ", stdout, StringComparison.Ordinal);
    }
}
