using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Color;

namespace SpectralRenderer.Imaging;

/// <summary>
/// Eq. 3 for every pixel at once: X, Y, Z planes (double) from band-sequential planes (<see cref="Spectra.SpectralImage.CopyBands"/>).
/// Each pixel's value is bit-equal to <see cref="Colorimeter.ToXyz(ReadOnlySpan{float})"/> of its spectrum: the same
/// products W[b]·(double)v[b], summed from zero in band order, a vector lane per pixel and no fused multiply-add.
/// Shared by the preview and the R, G, B / X, Y, Z channels of spectral.exr.
/// </summary>
public sealed class XyzPlanes
{
    XyzPlanes(double[] x, double[] y, double[] z) { X = x; Y = y; Z = z; }

    public double[] X { get; }
    public double[] Y { get; }
    public double[] Z { get; }

    public Xyz this[int pixel] => new(X[pixel], Y[pixel], Z[pixel]);

    /// <summary>The planes of colours the renderer computed per pixel (X, Y, Z interleaved, as the renderer's result holds them).</summary>
    public static XyzPlanes FromPixels(float[] interleaved)
    {
        int pixels = interleaved.Length / 3;
        var xyz = new XyzPlanes(new double[pixels], new double[pixels], new double[pixels]);
        for (int i = 0; i < pixels; i++)
        {
            xyz.X[i] = interleaved[3 * i];
            xyz.Y[i] = interleaved[3 * i + 1];
            xyz.Z[i] = interleaved[3 * i + 2];
        }
        return xyz;
    }

    public static XyzPlanes Compute(Colorimeter cm, ReadOnlyMemory<float> bands, int pixels)
    {
        int count = cm.Grid.Count;
        if (bands.Length != pixels * count)
            throw new ArgumentException($"band planes hold {bands.Length} values, {pixels}×{count} expected");
        var xyz = new XyzPlanes(new double[pixels], new double[pixels], new double[pixels]);
        const int Block = 2048;   // pixels per step: the three accumulator runs (48 KB) stay in L2 across the bands
        Parallel.For(0, (pixels + Block - 1) / Block, k =>
        {
            int p0 = k * Block;
            xyz.Accumulate(cm, bands.Span, pixels, p0, Math.Min(Block, pixels - p0));
        });
        return xyz;
    }

    /// <summary>The same planes from the pixel-interleaved cube, pixel by pixel (for a preview without band planes).</summary>
    public static XyzPlanes Compute(Colorimeter cm, Spectra.SpectralImage image)
    {
        int pixels = image.Width * image.Height, count = image.Bands;
        var xyz = new XyzPlanes(new double[pixels], new double[pixels], new double[pixels]);
        Parallel.For(0, image.Height, [MethodImpl(MethodImplOptions.AggressiveOptimization)] (row) =>
        {
            for (int p = row * image.Width; p < (row + 1) * image.Width; p++)
            {
                var v = cm.ToXyz((ReadOnlySpan<float>)image.Data.AsSpan(p * count, count));
                xyz.X[p] = v.X; xyz.Y[p] = v.Y; xyz.Z[p] = v.Z;
            }
        });
        return xyz;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void Accumulate(Colorimeter cm, ReadOnlySpan<float> bands, int pixels, int p0, int n)
    {
        Span<double> x = X.AsSpan(p0, n), y = Y.AsSpan(p0, n), z = Z.AsSpan(p0, n);
        for (int b = 0; b < cm.Grid.Count; b++)
        {
            var v = bands.Slice(b * pixels + p0, n);
            double wx = cm.Wx[b], wy = cm.Wy[b], wz = cm.Wz[b];
            int i = 0;
            if (Vector.IsHardwareAccelerated)
            {
                Vector<double> vx = new(wx), vy = new(wy), vz = new(wz);
                int d = Vector<double>.Count;
                for (; i + 2 * d <= n; i += 2 * d)
                {
                    Vector.Widen(new Vector<float>(v[i..]), out var lo, out var hi);   // float → double is exact
                    (new Vector<double>(x[i..]) + vx * lo).CopyTo(x[i..]);
                    (new Vector<double>(x[(i + d)..]) + vx * hi).CopyTo(x[(i + d)..]);
                    (new Vector<double>(y[i..]) + vy * lo).CopyTo(y[i..]);
                    (new Vector<double>(y[(i + d)..]) + vy * hi).CopyTo(y[(i + d)..]);
                    (new Vector<double>(z[i..]) + vz * lo).CopyTo(z[i..]);
                    (new Vector<double>(z[(i + d)..]) + vz * hi).CopyTo(z[(i + d)..]);
                }
            }
            for (; i < n; i++) { x[i] += wx * v[i]; y[i] += wy * v[i]; z[i] += wz * v[i]; }
        }
    }
}
