using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Spectra;

/// <summary>
/// A multispectral image: Height × Width pixels × Grid.Count bands of float32 spectral radiance,
/// stored pixel-interleaved in C order (row y, column x, band b at (y·Width + x)·Bands + b),
/// which is also the NumPy layout H × W × N. Row 0 is the top of the picture.
/// </summary>
public sealed class SpectralImage
{
    public SpectralImage(int width, int height, BandGrid grid, float[]? data = null)
    {
        if (width < 1 || height < 1) throw new ArgumentOutOfRangeException(nameof(width));
        Width = width;
        Height = height;
        Grid = grid;
        long n = (long)width * height * grid.Count;
        if (n > Array.MaxLength) throw new OutOfMemoryException($"{width}×{height}×{grid.Count} floats exceed one array");
        Data = data ?? new float[n];
        if (Data.Length != n) throw new ArgumentException("data length does not match width × height × bands");
    }

    public int Width { get; }
    public int Height { get; }
    public BandGrid Grid { get; }
    public int Bands => Grid.Count;
    public float[] Data { get; }

    public int Offset(int x, int y) => (y * Width + x) * Bands;
    public Span<float> Pixel(int x, int y) => Data.AsSpan(Offset(x, y), Bands);
    public float this[int x, int y, int band] { get => Data[Offset(x, y) + band]; set => Data[Offset(x, y) + band] = value; }

    /// <summary>Copies band b into a row-major Height × Width plane.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public void CopyBand(int band, Span<float> plane)
    {
        for (int i = 0, p = band; i < Width * Height; i++, p += Bands) plane[i] = Data[p];
    }

    /// <summary>
    /// Copies pixels [firstPixel, firstPixel + pixelCount) of every band into band-sequential planes: band b's
    /// row-major Height × Width plane starts at b·Width·Height (ENVI's BSQ order). One blocked transpose: a block of
    /// pixels is read once from cache and scattered as one short run per band, instead of a strided pass per band.
    /// Disjoint pixel ranges may be copied concurrently.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public void CopyBands(Span<float> planes, int firstPixel = 0, int pixelCount = -1)
    {
        int n = Width * Height, bands = Bands;
        if (pixelCount < 0) pixelCount = n - firstPixel;
        if (planes.Length < n * bands) throw new ArgumentException($"band planes hold {planes.Length} values, {n * bands} needed");
        ArgumentOutOfRangeException.ThrowIfNegative(firstPixel);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(pixelCount, n - firstPixel);
        const int Block = 256;  // 256 pixels × 20 bands × 4 B = 20 KB in: stays in L1 while each band takes its 1 KB run
        for (int p0 = firstPixel, end = firstPixel + pixelCount; p0 < end; p0 += Block)
        {
            int count = Math.Min(Block, end - p0);
            ReadOnlySpan<float> block = Data.AsSpan(p0 * bands, count * bands);
            for (int b = 0; b < bands; b++)
            {
                var run = planes.Slice(b * n + p0, count);
                for (int i = 0, s = b; i < run.Length; i++, s += bands) run[i] = block[s];
            }
        }
    }

    /// <summary>All bands as band-sequential planes (see <see cref="CopyBands"/>), copied on all cores.</summary>
    public float[] BandPlanes()
    {
        // Every value is written below: no zeroing pass first (the 84 MB of a 1024², 20-band cube).
        var planes = LargeArrays.Uninitialized<float>(Data.Length);
        int n = Width * Height;
        const int Parts = 16;
        Parallel.For(0, Parts, part =>
        {
            int p0 = (int)((long)n * part / Parts), p1 = (int)((long)n * (part + 1) / Parts);
            CopyBands(planes, p0, p1 - p0);
        });
        return planes;
    }

    /// <summary>The maximum value over all pixels and bands (the common scale of the band images).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public float Max()
    {
        // Per lane "take v when v > m", as the scalar loop does: NaNs never compare greater and are skipped.
        float m = 0;
        int i = 0;
        if (Vector.IsHardwareAccelerated && Data.Length >= Vector<float>.Count)
        {
            var acc = Vector<float>.Zero;
            for (; i + Vector<float>.Count <= Data.Length; i += Vector<float>.Count)
            {
                var v = new Vector<float>(Data.AsSpan(i));
                acc = Vector.ConditionalSelect(Vector.GreaterThan(v, acc), v, acc);
            }
            for (int k = 0; k < Vector<float>.Count; k++) if (acc[k] > m) m = acc[k];
        }
        for (; i < Data.Length; i++) if (Data[i] > m) m = Data[i];
        return m;
    }
}
