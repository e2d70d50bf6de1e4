using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A density grid placed in the scene: nx × ny × nz samples, x fastest (index (z·ny + y)·nx + x, the order of Mitsuba's
/// <c>.vol</c> files and of a C-order NumPy array indexed [z, y, x]), spread over the axis-aligned box
/// [<see cref="Min"/>, <see cref="Max"/>] in scene units. Sample (i, j, k) sits at the centre of its cell, Min + (i + ½, j + ½,
/// k + ½)·(Max − Min)/(nx, ny, nz) (as Mitsuba 3's grid volume); between the samples the density is trilinear, towards the
/// faces of the box it is held at the outermost sample, and outside the box it is 0.
/// </summary>
public sealed class DensityGrid
{
    readonly float[] _data;
    readonly int _nx, _ny, _nz;
    readonly Vector3 _scale;   // cells per scene unit along each axis

    /// <param name="data">nx·ny·nz densities, x fastest, each finite and ≥ 0 (the readers check).</param>
    public DensityGrid(float[] data, int nx, int ny, int nz, Vector3 min, Vector3 max)
    {
        if (nx < 1 || ny < 1 || nz < 1 || (long)nx * ny * nz != data.Length)
            throw new ArgumentException($"{data.Length} densities for a {nx} × {ny} × {nz} grid");
        if (!(min.X < max.X && min.Y < max.Y && min.Z < max.Z)) throw new ArgumentException("empty grid bounds");
        _data = data; _nx = nx; _ny = ny; _nz = nz; Min = min; Max = max;
        _scale = new Vector3(nx, ny, nz) / (max - min);
        float m = 0;
        foreach (float v in data) m = MathF.Max(m, v);
        Maximum = m;
    }

    public Vector3 Min { get; }
    public Vector3 Max { get; }
    public int Nx => _nx;
    public int Ny => _ny;
    public int Nz => _nz;
    /// <summary>The largest density: trilinear interpolation never exceeds it (the tracking's majorant).</summary>
    public float Maximum { get; }

    /// <summary>The density at scene point <paramref name="p"/> (0 outside the box).</summary>
    public float Density(Vector3 p)
    {
        var u = (p - Min) * _scale;   // in cells from the box's corner
        if (!(u.X >= 0 && u.Y >= 0 && u.Z >= 0 && u.X <= _nx && u.Y <= _ny && u.Z <= _nz)) return 0;
        return (float)Trilinear(u.X - 0.5, u.Y - 0.5, u.Z - 0.5);
    }

    /// <summary>The trilinear density at grid coordinates (g = 0: the first sample), held at the outermost samples.</summary>
    double Trilinear(double gx, double gy, double gz)
    {
        gx = Math.Clamp(gx, 0, _nx - 1); gy = Math.Clamp(gy, 0, _ny - 1); gz = Math.Clamp(gz, 0, _nz - 1);
        int x0 = Math.Min((int)gx, _nx - 1), y0 = Math.Min((int)gy, _ny - 1), z0 = Math.Min((int)gz, _nz - 1);
        int x1 = Math.Min(x0 + 1, _nx - 1), y1 = Math.Min(y0 + 1, _ny - 1), z1 = Math.Min(z0 + 1, _nz - 1);
        double fx = gx - x0, fy = gy - y0, fz = gz - z0;
        double Lerp(int y, int z)
        {
            int row = (z * _ny + y) * _nx;
            return _data[row + x0] + fx * (_data[row + x1] - _data[row + x0]);
        }
        double c0 = Lerp(y0, z0) + fy * (Lerp(y1, z0) - Lerp(y0, z0));
        double c1 = Lerp(y0, z1) + fy * (Lerp(y1, z1) - Lerp(y0, z1));
        return c0 + fz * (c1 - c0);
    }

    /// <summary>
    /// Where the ray from <paramref name="origin"/> along <paramref name="direction"/> is inside the box, clipped to
    /// [0, <paramref name="distance"/>]: false when it misses it.
    /// </summary>
    public bool Clip(Vector3 origin, Vector3 direction, float distance, out float near, out float far)
    {
        near = 0; far = distance;
        for (int a = 0; a < 3; a++)
        {
            float o = origin[a], d = direction[a], lo = Min[a], hi = Max[a];
            if (d == 0) { if (o < lo || o > hi) return false; continue; }
            float t0 = (lo - o) / d, t1 = (hi - o) / d;
            if (t0 > t1) (t0, t1) = (t1, t0);
            near = MathF.Max(near, t0); far = MathF.Min(far, t1);
        }
        return near < far;
    }

    /// <summary>
    /// τ = ∫₀ᵗ density(o + sω) ds along the ray for <paramref name="distance"/> (+∞ allowed), exact: the ray's overlap with
    /// the box is cut where it crosses a plane of samples along any axis; on each piece every grid coordinate is linear in
    /// s between the same two samples (or held), so the trilinear density is a cubic in s and Simpson's rule,
    /// (h/6)·(f₀ + 4f½ + f₁), integrates it exactly.
    /// </summary>
    public double OpticalDepth(Vector3 origin, Vector3 direction, float distance)
    {
        if (!Clip(origin, direction, distance, out float near, out float far)) return 0;
        Span<double> g0 = stackalloc double[3], slope = stackalloc double[3], next = stackalloc double[3];
        Span<int> plane = stackalloc int[3], step = stackalloc int[3], count = [_nx, _ny, _nz];
        for (int a = 0; a < 3; a++)
        {
            double cells = count[a] / ((double)Max[a] - Min[a]);
            g0[a] = ((double)origin[a] - Min[a]) * cells - 0.5;   // grid coordinate at s = 0
            slope[a] = direction[a] * cells;
            double g = g0[a] + slope[a] * near;
            step[a] = slope[a] > 0 ? 1 : slope[a] < 0 ? -1 : 0;
            plane[a] = step[a] > 0 ? (int)Math.Floor(g) + 1 : (int)Math.Ceiling(g) - 1;
            next[a] = NextCrossing(a, g0, slope, plane, step, count);
        }
        double tau = 0, t = near, f = At(g0, slope, t);
        while (t < far)
        {
            int a = next[0] <= next[1] ? next[0] <= next[2] ? 0 : 2 : next[1] <= next[2] ? 1 : 2;
            double end = Math.Min(next[a], far);
            if (end > t)
            {
                double fEnd = At(g0, slope, end);
                tau += (end - t) / 6 * (f + 4 * At(g0, slope, 0.5 * (t + end)) + fEnd);
                f = fEnd; t = end;
            }
            if (next[a] >= far) break;
            plane[a] += step[a];
            next[a] = NextCrossing(a, g0, slope, plane, step, count);
        }
        return tau;
    }

    double At(ReadOnlySpan<double> g0, ReadOnlySpan<double> slope, double s) =>
        Trilinear(g0[0] + slope[0] * s, g0[1] + slope[1] * s, g0[2] + slope[2] * s);

    /// <summary>Where the ray crosses sample plane <c>plane[a]</c> of axis a (+∞: none left inside the samples).</summary>
    static double NextCrossing(int a, ReadOnlySpan<double> g0, ReadOnlySpan<double> slope, ReadOnlySpan<int> plane,
        ReadOnlySpan<int> step, ReadOnlySpan<int> count) =>
        step[a] == 0 || plane[a] < 0 || plane[a] > count[a] - 1 ? double.PositiveInfinity : (plane[a] - g0[a]) / slope[a];
}
