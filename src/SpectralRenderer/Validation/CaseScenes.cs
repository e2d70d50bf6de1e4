using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Illumination;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Validation;

/// <summary>What the cases share: scenes from JSON text in memory, numbers written into them, a folder for the files a
/// scene names (photometric files), sample statistics, and the illuminance measured at free points.</summary>
internal static class CaseScenes
{
    /// <summary>A number as JSON writes it (invariant, round-trip).</summary>
    internal static string F(double v) => v.ToString("R", CultureInfo.InvariantCulture);

    /// <summary>A vector as a JSON array.</summary>
    internal static string V(Vector3 v) => $"[{F(v.X)}, {F(v.Y)}, {F(v.Z)}]";

    /// <summary>A light's (emitter's, sky's) value as the case writes it into the scene: × the test hook's scale.</summary>
    internal static string Light(double value) => F(value * Perturbation.LightScale);

    /// <summary>The scene of <paramref name="json"/>, loaded as if it were <paramref name="folder"/>/validate.json.</summary>
    internal static Scene Load(string json, string? folder = null) =>
        SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(folder ?? Path.GetTempPath(), "validate.json"));

    /// <summary>A scratch folder for a case's files, removed when disposed.</summary>
    internal sealed class Folder : IDisposable
    {
        public string Path { get; } = Directory.CreateTempSubdirectory("spectral-validate-").FullName;

        public string Write(string name, string text)
        {
            var file = System.IO.Path.Combine(Path, name);
            File.WriteAllText(file, text);
            return file;
        }

        public void Dispose()
        {
            try { Directory.Delete(Path, recursive: true); }
            catch (IOException) { }
            catch (UnauthorizedAccessException) { }
        }
    }

    /// <summary>The mean of <paramref name="x"/> and its standard error s/√n.</summary>
    internal static (double Mean, double Sigma) MeanAndError(IReadOnlyList<double> x)
    {
        double mean = x.Average();
        if (x.Count < 2) return (mean, 0);
        double ss = x.Sum(v => (v - mean) * (v - mean));
        return (mean, Math.Sqrt(ss / (x.Count - 1) / x.Count));
    }

    /// <summary>
    /// The direct illuminance (lx) at each free point p with normal n (the test hook's tilt applied), from the engine's
    /// <see cref="Illuminance.Direct"/>, each point measured <paramref name="seeds"/> times with independent sample
    /// streams: the mean and its standard error per point (exact lights: σ = 0).
    /// </summary>
    internal static (double Mean, double Sigma)[] Direct(Scene scene, IReadOnlyList<(Vector3 P, Vector3 N)> points, int seeds,
        CaseContext context)
    {
        var illuminance = new Illuminance(scene, new SceneGeometry(scene));
        var result = new (double, double)[points.Count];
        var options =
            new ParallelOptions { MaxDegreeOfParallelism = context.Threads > 0 ? context.Threads : -1, CancellationToken = context.Cancel };
        Parallel.For(0, points.Count, options, i =>
        {
            var (p, n0) = points[i];
            var n = Perturbation.Receiver(n0);
            var counters = new RayCounters();
            var e = new double[seeds];
            for (int s = 0; s < seeds; s++) e[s] = illuminance.Direct(s, i, p, n, n, false, ref counters);
            result[i] = MeanAndError(e);
        });
        return result;
    }

    /// <summary>
    /// The illuminance (lx) of the engine's path-traced gather (direct share plus π/N Σ L_v of N cosine-weighted paths) at
    /// each free point, as <see cref="Illuminance.OnGrid"/> measures a calculation grid: each point is a small grid of
    /// k × k points within 10 µm of it (independent sample streams: a stream per point), their mean and its standard error.
    /// </summary>
    internal static (double Mean, double Sigma)[] Gathered(Scene scene, IReadOnlyList<(Vector3 P, Vector3 N)> points, int k,
        CaseContext context)
    {
        var geometry = new SceneGeometry(scene);
        var illuminance = new Illuminance(scene, geometry);
        var gather = Rendering.Registry.Integrators.Create(scene, geometry, "path") as IGatherIntegrator
            ?? throw new InvalidOperationException("the path integrator gathers");
        var result = new (double, double)[points.Count];
        for (int i = 0; i < points.Count; i++)
        {
            var (p, n0) = points[i];
            var n = Perturbation.Receiver(n0);
            var u = Vector3.Normalize(Vector3.Cross(n, MathF.Abs(n.Y) < 0.9f ? Vector3.UnitY : Vector3.UnitX)) * 1e-5f;
            var v = Vector3.Cross(n, u);   // u × (n × u) = |u|²·n: the grid faces n
            var grid = new CalculationGrid("point", p - 0.5f * (u + v), u, v, k, k);
            result[i] = MeanAndError(illuminance.OnGridWithError(grid, gather, context.Threads, 0, i, null, context.Cancel).Lux);
        }
        return result;
    }
}
