using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Textures;

/// <summary>
/// A reflectance image: Height × Width texels, each a spectrum tabulated at the same <see cref="Wavelengths"/> (an ENVI
/// cube's or spectral EXR's band centres, a PNG stack's list, or an RGB texel's uplifted spectrum on its own grid),
/// linear between the samples like every table here. Row 0 is the top of the image (v = 1). The texel spectra are
/// projected onto a render's bands and colour by the renderer's texture tables, exactly, once per render.
/// </summary>
public sealed class SpectralTexture
{
    /// <param name="values">Texel-major: sample j of texel (x, y) at (y·width + x)·wavelengths.Length + j.</param>
    public SpectralTexture(string source, int width, int height, double[] wavelengths, float[] values, Extrapolation extrapolation = Extrapolation.Clamp)
    {
        if (width < 1 || height < 1) throw new ArgumentOutOfRangeException(nameof(width), "a texture needs at least one texel");
        if ((long)width * height * wavelengths.Length != values.Length) throw new ArgumentException("values must hold width × height × wavelengths samples", nameof(values));
        Source = source;
        Width = width;
        Height = height;
        Wavelengths = wavelengths;
        Values = values;
        Extrapolation = extrapolation;
    }

    /// <summary>Where it came from (a file), for messages and the manifest.</summary>
    public string Source { get; }
    public int Width { get; }
    public int Height { get; }
    public double[] Wavelengths { get; }
    public float[] Values { get; }
    /// <summary>How each texel's table continues beyond its first and last wavelength.</summary>
    public Extrapolation Extrapolation { get; }
    public int Samples => Wavelengths.Length;

    /// <summary>Texel (x, y)'s samples.</summary>
    public ReadOnlySpan<float> Texel(int x, int y) => Values.AsSpan((y * Width + x) * Samples, Samples);

    /// <summary>Texel (x, y) as a spectrum.</summary>
    public TabulatedSpectrum Spectrum(int x, int y)
    {
        var t = Texel(x, y);
        var v = new double[Samples];
        for (int j = 0; j < v.Length; j++) v[j] = t[j];
        return new TabulatedSpectrum($"{Source}[{x},{y}]", Wavelengths, v, Extrapolation);
    }

    /// <summary>The mean spectrum over the texels (what the texture looks like from afar; the material's untextured view).</summary>
    public TabulatedSpectrum Mean()
    {
        var sum = new double[Samples];
        for (int i = 0; i < Values.Length; i++) sum[i % Samples] += Values[i];
        for (int j = 0; j < sum.Length; j++) sum[j] /= (double)Width * Height;
        return new TabulatedSpectrum($"{Source} (mean)", Wavelengths, sum, Extrapolation);
    }

    /// <summary>The smallest and largest sample.</summary>
    public (float Min, float Max) Range()
    {
        float min = float.PositiveInfinity, max = float.NegativeInfinity;
        foreach (float v in Values) { min = MathF.Min(min, v); max = MathF.Max(max, v); }
        return (min, max);
    }
}
