using System.Runtime.CompilerServices;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

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

    /// <summary>The maximum value over all pixels and bands (the common scale of the band images).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public float Max()
    {
        float m = 0;
        foreach (var v in Data) if (v > m) m = v;
        return m;
    }
}
