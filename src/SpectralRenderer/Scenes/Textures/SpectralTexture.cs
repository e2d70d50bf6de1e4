using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Textures;

/// <summary>A texture's texels as they are read: a block of whole rows at a time, texel-major (sample j of texel x of the
/// block's row r at (r·width + x)·samples + j). A file's cube is read from the file at each pass, not held.</summary>
public abstract class TexelRows
{
    /// <summary>Rows <paramref name="y0"/> … <paramref name="y0"/> + <paramref name="rows"/> − 1 into <paramref name="dst"/>.</summary>
    public abstract void Read(int y0, int rows, Span<float> dst);
}

/// <summary>Texels held in memory, texel-major (an uplifted RGB image, a spectral EXR as its reader gives it).</summary>
public sealed class TexelArray(float[] values, int rowFloats) : TexelRows
{
    public override void Read(int y0, int rows, Span<float> dst) =>
        values.AsSpan(checked(y0 * rowFloats), rows * rowFloats).CopyTo(dst);
}

/// <summary>
/// A reflectance image: Height × Width texels, each a spectrum tabulated at the same <see cref="Wavelengths"/> (an ENVI
/// cube's or spectral EXR's band centres, a PNG stack's list, or an RGB texel's uplifted spectrum on its own grid),
/// linear between the samples like every table here. Row 0 is the top of the image (v = 1). The texel spectra are
/// projected onto a render's bands and colour by the renderer's texture tables, exactly, once per render, read a block
/// of rows at a time (<see cref="ForEachBlock"/>), so a cube read from a file is never held whole.
/// </summary>
public sealed class SpectralTexture
{
    /// <summary>Floats a block of rows holds at most (16 MiB; one row when a row is longer).</summary>
    public const int BlockFloats = 1 << 22;
    /// <summary>Floats a block holds on this flow instead (tests: a texture read in several blocks).</summary>
    internal static readonly AsyncLocal<int?> BlockOverride = new();

    readonly TexelRows _rows;
    readonly List<double> _factors = [];

    /// <param name="values">Texel-major: sample j of texel (x, y) at (y·width + x)·wavelengths.Length + j.</param>
    public SpectralTexture(string source, int width, int height, double[] wavelengths, float[] values,
        Extrapolation extrapolation = Extrapolation.Clamp)
        : this(source, width, height, wavelengths, new TexelArray(values, width * wavelengths.Length), extrapolation)
    {
        if ((long)width * height * wavelengths.Length != values.Length)
            throw new ArgumentException("values must hold width × height × wavelengths samples", nameof(values));
    }

    /// <summary>A texture whose texels <paramref name="rows"/> reads.</summary>
    public SpectralTexture(string source, int width, int height, double[] wavelengths, TexelRows rows,
        Extrapolation extrapolation = Extrapolation.Clamp)
    {
        if (width < 1 || height < 1) throw new ArgumentOutOfRangeException(nameof(width), "a texture needs at least one texel");
        if ((long)width * wavelengths.Length > Array.MaxLength)
            throw new ArgumentOutOfRangeException(nameof(width), "a row of the texture exceeds one array");
        Source = source;
        Width = width;
        Height = height;
        Wavelengths = wavelengths;
        _rows = rows;
        Extrapolation = extrapolation;
    }

    /// <summary>Where it came from (a file), for messages and the manifest.</summary>
    public string Source { get; }
    public int Width { get; }
    public int Height { get; }
    public double[] Wavelengths { get; }
    /// <summary>How each texel's table continues beyond its first and last wavelength.</summary>
    public Extrapolation Extrapolation { get; }
    public int Samples => Wavelengths.Length;
    /// <summary>Rows a block holds (<see cref="BlockFloats"/>).</summary>
    public int BlockRows => (int)Math.Clamp((BlockOverride.Value ?? BlockFloats) / ((long)Width * Samples), 1, Height);

    /// <summary>Every texel's value times <paramref name="factor"/> from now on (each factor rounded to float in turn, as a
    /// scaling of the values in place would be).</summary>
    public void Scale(double factor)
    {
        if (factor != 1) _factors.Add(factor);
    }

    /// <summary>Rows <paramref name="y0"/> … <paramref name="y0"/> + <paramref name="rows"/> − 1 into <paramref name="dst"/>,
    /// texel-major, scaled.</summary>
    public void ReadRows(int y0, int rows, Span<float> dst)
    {
        dst = dst[..checked(rows * Width * Samples)];
        _rows.Read(y0, rows, dst);
        foreach (double f in _factors)
            for (int i = 0; i < dst.Length; i++) dst[i] = (float)(dst[i] * f);
    }

    /// <summary>The texture top to bottom, a block of <see cref="BlockRows"/> rows at a time: <paramref name="block"/> gets
    /// the block's first row, its rows and their texels (one buffer for every block).</summary>
    public void ForEachBlock(Action<int, int, float[]> block)
    {
        int n = BlockRows;
        var buffer = new float[n * Width * Samples];
        for (int y0 = 0; y0 < Height; y0 += n)
        {
            int rows = Math.Min(n, Height - y0);
            ReadRows(y0, rows, buffer);
            block(y0, rows, buffer);
        }
    }

    /// <summary>A texel's samples (<paramref name="texel"/>) as a spectrum named by its place (x, y).</summary>
    public TabulatedSpectrum Spectrum(ReadOnlySpan<float> texel, int x, int y)
    {
        var v = new double[Samples];
        for (int j = 0; j < v.Length; j++) v[j] = texel[j];
        return new TabulatedSpectrum($"{Source}[{x},{y}]", Wavelengths, v, Extrapolation);
    }

    /// <summary>The smallest and largest sample and the mean spectrum over the texels (what the texture looks like from afar;
    /// the material's untextured view), in one pass.</summary>
    public (float Min, float Max, TabulatedSpectrum Mean) Summary()
    {
        float min = float.PositiveInfinity, max = float.NegativeInfinity;
        var sum = new double[Samples];
        int samples = Samples;
        ForEachBlock((_, rows, block) =>
        {
            int n = rows * Width * samples;
            for (int i = 0; i < n; i++)
            {
                float v = block[i];
                min = MathF.Min(min, v); max = MathF.Max(max, v);
                sum[i % samples] += v;
            }
        });
        for (int j = 0; j < sum.Length; j++) sum[j] /= (double)Width * Height;
        return (min, max, new TabulatedSpectrum($"{Source} (mean)", Wavelengths, sum, Extrapolation));
    }
}
