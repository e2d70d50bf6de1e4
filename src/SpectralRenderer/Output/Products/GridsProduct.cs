using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Illumination;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>
/// "grids" (set by a scene's "calculation_grids"; physical radiometry): grids/NAME.csv and grids/NAME.svg for each
/// calculation grid, the illuminance (lx) at its points (<see cref="Illuminance.OnGrid"/>) from every light with shadows
/// and, under an integrator that gathers (<see cref="IGatherIntegrator"/>: path), area lights, sky and interreflection.
/// A relit render traces the grid again
/// under its own lights (the scene's geometry built once more). Not per pixel: every shard writes the same files.
/// </summary>
public sealed class GridsProduct : OutputProduct
{
    public override string Name => "grids";
    public override OutputProducts Flag => OutputProducts.Grids;

    public override void Write(ProductContext c, int part, Action<string> done)
    {
        var scene = c.Scene;
        if (scene.CalculationGrids.Count == 0) return;
        var geometry = c.Tracer?.Geometry ?? new SceneGeometry(scene);
        var integrator = c.Tracer?.Integrator ?? Integrators.Create(scene, geometry, scene.Integrator?.Name ?? Integrators.Default);
        var illuminance = new Illuminance(scene, geometry);
        var dir = Path.Combine(c.OutDir, CalculationGridFiles.Folder);
        Directory.CreateDirectory(dir);
        string title = Path.GetFileName(scene.SourcePath);
        for (int k = 0; k < scene.CalculationGrids.Count; k++)
        {
            var grid = scene.CalculationGrids[k];
            // A gathered grid samples to the render's target error (--target-error) and has a standard-error column.
            var lux = illuminance.OnGridWithError(grid, integrator as IGatherIntegrator, c.Tracer?.Threads ?? 0, scene.TargetError, k,
                integrator is IGatherIntegrator ? c.StageProgress($"grid {grid.Name} gather") : null, c.Cancel);
            CalculationGridFiles.Write(Path.Combine(dir, grid.Name), grid, lux.Lux, $"{title}: {grid.Name}", lux.StandardError);
            done($"{CalculationGridFiles.Folder}/{grid.Name}.csv");
            done($"{CalculationGridFiles.Folder}/{grid.Name}.svg");
        }
    }

    public override ShardMerging Merging(string file) => ShardMerging.Copy;

    public override bool Owns(string file) => file.StartsWith(CalculationGridFiles.Folder + "/", StringComparison.Ordinal);
}
