using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// The sky of an environment map (<see cref="EnvironmentMap"/>: Mitsuba 3's lat-long conventions, pixels as the vertices of
/// a bilinear grid): every escaping ray sees <see cref="Lookup"/> of its direction. Each pixel's unit spectrum is projected onto
/// the sub-band grid once (W·H·sub-bands floats). Next-event estimation samples the grid's cells, W columns (the last wraps to
/// the first) × (H − 1) rows, each with probability ∝ its largest corner luminance × the solid angle cos θ_y − cos θ_y+1 of
/// its row (so a cell that sends any light can be drawn), then (u, v) uniformly in the cell: a 2D piecewise-constant
/// density in (u, v) (marginal rows, conditional columns: Pharr, Jakob &amp; Humphreys, PBR 4th ed. §A.5.3), whose solid-angle
/// density is p(u, v)/(2π² sin θ). <see cref="Emitter.Radiance"/> is the map's mean, which the power of the emitter set's
/// choice uses (Φ = 4π²R² × mean, as the uniform sky's).
/// <para>An equal-area square (<see cref="EnvironmentMapping.EqualArea"/>, pbrt-v4's) is piecewise constant over its N × N
/// pixels, each 4π/N² (<see cref="EqualAreaSquare"/>): the radiance is the pixel's, the cells are the pixels (weight: the
/// luminance), and the solid-angle density of (u, v) in the square is p(u, v)/4π.</para>
/// </summary>
internal sealed class EnvironmentEmitter : Emitter
{
    readonly int _w, _h, _padded, _count;
    readonly bool _equalArea;   // pbrt's square: the cells are the pixels (no wrap, no corners), a pixel's radiance is constant
    readonly float[] _unit;     // [(y·W + x)·padded + f]: the pixel's unit spectrum on the sub-band grid
    readonly float[] _scale;    // [y·W + x]: s = 2·max(r, g, b)·Scale
    readonly float[] _rowCdf;   // H − 1 + 1 running sums of the rows' weights, normalised, [0] = 0
    readonly float[] _colCdf;   // (H − 1) × (W + 1): per row, running sums of its cells', normalised, [0] = 0
    readonly float[] _cellPdf;  // (H − 1) × W: p(u, v) of each cell (density over the unit square)
    readonly Matrix4x4 _toLocal, _toWorld;

    public EnvironmentEmitter(EnvironmentMap map, SubBandGrid grid) : base(Mean(map, grid, out var unit, out var scale))
    {
        _w = map.Width;
        _h = map.Height;
        _padded = grid.Padded;
        _count = grid.Count;
        _unit = unit;
        _scale = scale;
        _toLocal = map.ToLocal;
        _toWorld = map.ToWorld;
        _equalArea = map.Mapping == EnvironmentMapping.EqualArea;
        // The cells' weights: the largest corner luminance (channel value) × the row's solid angle.
        var luminance = new double[_w * _h];
        for (int i = 0; i < luminance.Length; i++) luminance[i] = _scale[i] * grid.Luminance(_unit.AsSpan(i * _padded, _padded));
        int rows = Rows;
        _rowCdf = new float[rows + 1];
        _colCdf = new float[rows * (_w + 1)];
        _cellPdf = new float[rows * _w];
        var rowWeight = new double[rows];
        var cell = new double[_w];
        double total = 0;
        for (int y = 0; y < rows; y++)
        {
            double solid = _equalArea ? 1 : Math.Cos(Math.PI * y / rows) - Math.Cos(Math.PI * (y + 1) / rows);
            double sum = 0;
            for (int x = 0; x < _w; x++)
            {
                if (_equalArea)
                {
                    cell[x] = luminance[y * _w + x];
                    sum += cell[x];
                    continue;
                }
                int x1 = (x + 1) % _w;
                double l = Math.Max(Math.Max(luminance[y * _w + x], luminance[y * _w + x1]),
                    Math.Max(luminance[(y + 1) * _w + x], luminance[(y + 1) * _w + x1]));
                cell[x] = l * solid;
                sum += cell[x];
            }
            double running = 0;
            for (int x = 0; x < _w; x++)
            {
                running += cell[x];
                _colCdf[y * (_w + 1) + x + 1] = sum > 0 ? (float)(running / sum) : (float)(x + 1) / _w;
                _cellPdf[y * _w + x] = (float)cell[x];   // normalised below
            }
            _colCdf[y * (_w + 1) + _w] = 1;
            rowWeight[y] = sum;
            total += sum;
        }
        double acc = 0;
        for (int y = 0; y < rows; y++)
        {
            acc += rowWeight[y];
            _rowCdf[y + 1] = total > 0 ? (float)(acc / total) : 0;
        }
        _rowCdf[rows] = total > 0 ? 1 : 0;
        // p(u, v) = w_cell/Σw over a cell of area 1/(W·(H − 1)) in the unit square.
        for (int i = 0; i < _cellPdf.Length; i++) _cellPdf[i] = total > 0 ? (float)(_cellPdf[i] / total * _w * rows) : 0;
    }

    /// <summary>Each pixel's unit spectrum on the grid (exact sub-band means of its lattice blend) and scale, and the mean
    /// radiance over the sphere of the pixels taken over their cells' solid angles (<see cref="EnvironmentMap.RowSolidAngle"/>).</summary>
    static float[] Mean(EnvironmentMap map, SubBandGrid grid, out float[] unit, out float[] scale)
    {
        int n = map.Width * map.Height, padded = grid.Padded;
        unit = new float[n * padded];
        scale = new float[n];
        var cache = new Dictionary<TabulatedSpectrum, float[]>(ReferenceEqualityComparer.Instance);
        Span<(TabulatedSpectrum, double)> blend = new (TabulatedSpectrum, double)[8];
        var mean = new double[padded];
        double total = 0;
        for (int i = 0; i < n; i++)
        {
            double r = map.Rgb[3 * i], g = map.Rgb[3 * i + 1], b = map.Rgb[3 * i + 2];
            double m = Math.Max(r, Math.Max(g, b));
            if (!(m > 0)) continue;
            scale[i] = (float)(2 * m * map.Scale);
            map.UnitSpectrum(r / (2 * m), g / (2 * m), b / (2 * m), blend);
            var dst = unit.AsSpan(i * padded, padded);
            foreach (var (s, w) in blend)
            {
                if (w == 0) continue;
                if (!cache.TryGetValue(s, out var fine))
                {
                    fine = new float[padded];
                    for (int f = 0; f < grid.Count; f++) fine[f] = (float)s.Mean(grid.Lower[f], grid.Upper[f]);
                    cache[s] = fine;
                }
                for (int f = 0; f < grid.Count; f++) dst[f] += (float)(w * fine[f]);
            }
            double weight = map.RowSolidAngle(i / map.Width) * scale[i];
            for (int f = 0; f < grid.Count; f++) mean[f] += weight * dst[f];
        }
        for (int y = 0; y < map.Height; y++) total += map.RowSolidAngle(y) * map.Width;
        var result = new float[padded];
        for (int f = 0; f < grid.Count; f++) result[f] = (float)(mean[f] / total);
        return result;
    }

    /// <summary>The rows of sampling cells: H − 1 between a lat-long grid's pixel rows, or the square's N pixel rows.</summary>
    int Rows => _equalArea ? _h : _h - 1;

    public override bool IsDelta => false;

    /// <summary>Φ/L̄ = 4π·πR², L̄ the map's mean radiance (<see cref="SkyEmitter.PowerPerRadiance"/>).</summary>
    public override double PowerPerRadiance(double sceneRadius) => 4 * Math.PI * Math.PI * sceneRadius * sceneRadius;

    /// <summary>Every escaping ray sees the sky (its radiance by <see cref="Lookup"/>).</summary>
    public override float Emitted(Vector3 n, Vector3 wo) => 1;

    public override string Describe() => "sky (environment map)";

    public override bool Sample(Vector3 p, Vector3 front, Vector2 u, out EmitterSample sample)
    {
        sample = default;
        int rows = Rows;
        if (!(_rowCdf[rows] > 0)) return false;
        int y = Find(_rowCdf, 0, rows, u.Y);
        float dy = _rowCdf[y + 1] - _rowCdf[y];
        float fy = dy > 0 ? Math.Clamp((u.Y - _rowCdf[y]) / dy, 0, 1) : 0.5f;
        int o = y * (_w + 1);
        int x = Find(_colCdf, o, _w, u.X);
        float dx = _colCdf[o + x + 1] - _colCdf[o + x];
        float fx = dx > 0 ? Math.Clamp((u.X - _colCdf[o + x]) / dx, 0, 1) : 0.5f;
        float pdfUv = _cellPdf[y * _w + x];
        if (_equalArea)
        {
            if (!(pdfUv > 0)) return false;
            var square = EqualAreaSquare.ToSphere((x + fx) / _w, (y + fy) / _h);
            sample = new EmitterSample(Vector3.Normalize(Vector3.TransformNormal(square, _toWorld)), float.PositiveInfinity, 1,
                pdfUv / (4 * MathF.PI), false);
            return true;
        }
        // Grid coordinates (s, t) = (x + fx, y + fy): u = (s + ½)/W, θ = π·t/(H − 1).
        float uu = (x + fx + 0.5f) / _w, theta = MathF.PI * (y + fy) / rows;
        float sinTheta = MathF.Sin(theta);
        if (!(pdfUv > 0) || !(sinTheta > 0)) return false;
        float phi = 2 * MathF.PI * uu;
        var local = new Vector3(MathF.Sin(phi) * sinTheta, MathF.Cos(theta), -MathF.Cos(phi) * sinTheta);
        var wi = Vector3.Normalize(Vector3.TransformNormal(local, _toWorld));
        sample = new EmitterSample(wi, float.PositiveInfinity, 1, pdfUv / (2 * MathF.PI * MathF.PI * sinTheta), false);
        return true;
    }

    /// <summary>The solid-angle density of <see cref="Sample"/> drawing scene direction <paramref name="wi"/>.</summary>
    public override float Pdf(Vector3 p, Vector3 front, Vector3 wi, Vector3 x, Vector3 nx)
    {
        if (_equalArea) return _cellPdf[Pixel(wi)] / (4 * MathF.PI);
        Cell(wi, out int cx, out int cy, out _, out _, out float sinTheta);
        return sinTheta > 0 ? _cellPdf[cy * _w + cx] / (2 * MathF.PI * MathF.PI * sinTheta) : 0;
    }

    /// <summary>
    /// L(ω) of scene direction <paramref name="wi"/> (towards the sky) into <paramref name="radiance"/> (sub-band grid):
    /// (Σ w·u)(Σ w·s) over the bilinear weights w of the cell's four pixels (<see cref="EnvironmentMap"/>).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public ReadOnlySpan<float> Lookup(Vector3 wi, Span<float> radiance)
    {
        if (_equalArea)
        {
            int i = Pixel(wi);
            var o = MemoryMarshal.Cast<float, Vector<float>>(radiance[.._padded]);
            var p = MemoryMarshal.Cast<float, Vector<float>>(_unit.AsSpan(i * _padded, _padded));
            Vector<float> k = new(_scale[i]);
            for (int j = 0; j < o.Length; j++) o[j] = p[j] * k;
            return radiance[.._padded];
        }
        Cell(wi, out int x, out int y, out float fx, out float fy, out _);
        int x1 = x + 1 == _w ? 0 : x + 1;
        int i00 = y * _w + x, i10 = y * _w + x1, i01 = i00 + _w, i11 = i10 + _w;
        float w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
        float s = w00 * _scale[i00] + w10 * _scale[i10] + w01 * _scale[i01] + w11 * _scale[i11];
        var v = MemoryMarshal.Cast<float, Vector<float>>(radiance[.._padded]);
        var a = MemoryMarshal.Cast<float, Vector<float>>(_unit.AsSpan(i00 * _padded, _padded));
        var b = MemoryMarshal.Cast<float, Vector<float>>(_unit.AsSpan(i10 * _padded, _padded));
        var c = MemoryMarshal.Cast<float, Vector<float>>(_unit.AsSpan(i01 * _padded, _padded));
        var d = MemoryMarshal.Cast<float, Vector<float>>(_unit.AsSpan(i11 * _padded, _padded));
        Vector<float> v00 = new(w00 * s), v10 = new(w10 * s), v01 = new(w01 * s), v11 = new(w11 * s);
        for (int k = 0; k < v.Length; k++) v[k] = a[k] * v00 + b[k] * v10 + c[k] * v01 + d[k] * v11;
        return radiance[.._padded];
    }

    /// <summary>The grid cell (x, y), the position (fx, fy) in it and sin θ of scene direction <paramref name="wi"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    void Cell(Vector3 wi, out int x, out int y, out float fx, out float fy, out float sinTheta)
    {
        var d = Vector3.TransformNormal(wi, _toLocal);
        float len = d.Length();
        float cosTheta = Math.Clamp(d.Y / len, -1, 1);
        sinTheta = MathF.Sqrt(MathF.Max(0, 1 - cosTheta * cosTheta));
        float u = MathF.Atan2(d.X, -d.Z) * (0.5f / MathF.PI);
        float s = u * _w - 0.5f;   // u = (x + ½)/W at pixel column x
        s -= MathF.Floor(s / _w) * _w;
        x = Math.Min((int)s, _w - 1);
        fx = s - x;
        float t = MathF.Acos(cosTheta) / MathF.PI * (_h - 1);
        y = Math.Clamp((int)t, 0, _h - 2);
        fy = Math.Clamp(t - y, 0, 1);
    }

    /// <summary>The equal-area square's pixel y·N + x holding scene direction <paramref name="wi"/> (pbrt's nearest lookup).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    int Pixel(Vector3 wi)
    {
        var uv = EqualAreaSquare.ToSquare(Vector3.TransformNormal(wi, _toLocal));
        int x = Math.Clamp((int)(uv.X * _w), 0, _w - 1), y = Math.Clamp((int)(uv.Y * _h), 0, _h - 1);
        return y * _w + x;
    }

    /// <summary>The k in [0, n) with cdf[o + k] ≤ u &lt; cdf[o + k + 1] (the last non-empty one for u at the end).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static int Find(float[] cdf, int o, int n, float u)
    {
        int lo = 0, hi = n - 1;
        while (lo < hi)
        {
            int mid = (lo + hi) >> 1;
            if (u < cdf[o + mid + 1]) hi = mid;
            else lo = mid + 1;
        }
        // a zero-width interval (an empty row or cell) is never taken: step back to one with weight
        while (lo > 0 && !(cdf[o + lo + 1] > cdf[o + lo])) lo--;
        return lo;
    }
}
