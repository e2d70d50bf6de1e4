using System.Numerics;
using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes;

/// <summary>
/// An environment map: the sky's radiance from an equirectangular (latitude-longitude) linear sRGB image, in Mitsuba 3's
/// conventions (<c>envmap</c>), so a scene imported from Mitsuba sees the same sky:
/// <list type="bullet">
/// <item>Map space is +Y up. Image coordinates (u, v) ∈ [0, 1)² give φ = 2πu, θ = πv and the direction
/// d = (sin φ sin θ, cos θ, −cos φ sin θ): the image's top row is the zenith (+Y), its bottom row the nadir, the middle of
/// the image (u = ½, on the horizon) looks along +Z, u = ¼ along +X, the left and right edges along −Z (<see cref="Direction"/>,
/// <see cref="Uv"/>).</item>
/// <item>The pixels are the vertices of a grid that the radiance interpolates bilinearly: column x sits at u = (x + ½)/W
/// (wrapping round from the last column to the first), row y at θ = π·y/(H − 1) (the first row on the zenith, the last on the
/// nadir).</item>
/// <item>Each pixel's colour (times <see cref="Scale"/>) is uplifted as an illuminant (<see cref="IlluminantUplift"/>, D65):
/// s = 2·max(r, g, b) and the unit spectrum u(λ) = r(λ)·D65(λ)/Ȳ of rgb/s, and the radiance between pixels is
/// (Σ w·u)(Σ w·s), the bilinear weights w on each factor apart, as Mitsuba interpolates its coefficients and scales.</item>
/// <item><see cref="ToWorld"/> turns map directions into the scene's (Mitsuba's <c>to_world</c>, its linear part).</item>
/// </list>
/// The sigmoid uplift solves for each colour, too slow per pixel of a photograph; the unit spectra are instead taken at the
/// colours of a lattice of step 1/16 over rgb/s ∈ [0, ½]³ and interpolated trilinearly between them (<see cref="UnitSpectrum"/>):
/// colour is linear in the spectrum, so a pixel keeps its colour exactly (to the solves' ΔE), its spectrum's shape only is
/// a blend of its neighbours'. A colour on the lattice (each of rgb/s a multiple of 1/16) is uplifted exactly.
/// <para>With <see cref="EnvironmentMapping.EqualArea"/> the image is instead pbrt-v4's equal-area octahedral square
/// (<see cref="EqualAreaSquare"/>: N × N pixels of 4π/N² each, the square's centre along the map's +Z) and each pixel's radiance
/// holds over its whole area, as pbrt's nearest-pixel lookup; the uplift is the same.</para>
/// </summary>
public sealed class EnvironmentMap
{
    /// <summary>Lattice steps per unit of rgb/s (<see cref="UnitSpectrum"/>): 8 steps span [0, ½].</summary>
    public const int LatticeSteps = 16;

    readonly Dictionary<int, TabulatedSpectrum> _corners = [];
    readonly Lock _lock = new();
    readonly TabulatedSpectrum _d65;
    readonly double _luminanceFactor;

    /// <summary>A map of <paramref name="width"/> × <paramref name="height"/> pixels (linear RGB, rows top to bottom).</summary>
    public EnvironmentMap(string source, int width, int height, float[] rgb, double scale, Matrix4x4 toWorld,
        EnvironmentMapping mapping = EnvironmentMapping.LatLong)
    {
        if (mapping == EnvironmentMapping.LatLong && (width < 2 || height < 3))
            throw new ArgumentException("an environment map needs at least 2 × 3 pixels");
        if (mapping == EnvironmentMapping.EqualArea && (width < 1 || width != height))
            throw new ArgumentException("an equal-area map is a square of pixels");
        if (rgb.Length != 3 * width * height) throw new ArgumentException("the pixels do not match the size");
        Source = source;
        Width = width;
        Height = height;
        Rgb = rgb;
        Scale = scale;
        Mapping = mapping;
        ToWorld = toWorld with { M41 = 0, M42 = 0, M43 = 0 };
        if (!Matrix4x4.Invert(ToWorld, out var toLocal)) throw new ArgumentException("the map's transform is singular");
        ToLocal = toLocal;
        _d65 = SpectrumLibrary.Resolve("D65");
        _luminanceFactor = IlluminantUplift.LuminanceFactor(ref _d65);
    }

    /// <summary>The file it was read from (or a name).</summary>
    public string Source { get; }
    public int Width { get; }
    public int Height { get; }
    /// <summary>Linear RGB per pixel, rows top to bottom, before <see cref="Scale"/>.</summary>
    public float[] Rgb { get; }
    /// <summary>The factor on every pixel's radiance.</summary>
    public double Scale { get; }
    /// <summary>The image's layout: Mitsuba's lat-long grid or pbrt-v4's equal-area square.</summary>
    public EnvironmentMapping Mapping { get; }
    /// <summary>Map to scene directions (System.Numerics row-vector form: d_world = TransformNormal(d_map, ToWorld)).</summary>
    public Matrix4x4 ToWorld { get; }
    /// <summary>Scene to map directions, the inverse of <see cref="ToWorld"/>.</summary>
    public Matrix4x4 ToLocal { get; }

    /// <summary>The map-space unit direction of image coordinates (u, v): φ = 2πu, θ = πv (class summary).</summary>
    public static Vector3 Direction(double u, double v)
    {
        double phi = 2 * Math.PI * u, theta = Math.PI * v;
        return new Vector3((float)(Math.Sin(phi) * Math.Sin(theta)), (float)Math.Cos(theta), (float)(-Math.Cos(phi) * Math.Sin(theta)));
    }

    /// <summary>The image coordinates (u ∈ [0, 1), v ∈ [0, 1]) of map-space direction <paramref name="d"/> (any length).</summary>
    public static Vector2 Uv(Vector3 d)
    {
        d = Vector3.Normalize(d);
        float u = MathF.Atan2(d.X, -d.Z) / (2 * MathF.PI);
        if (u < 0) u += 1;
        if (u >= 1) u = 0;
        return new Vector2(u, MathF.Acos(Math.Clamp(d.Y, -1, 1)) / MathF.PI);
    }

    /// <summary>
    /// The unit spectrum u(λ) = r(λ)·D65(λ)/Ȳ of the normalised colour c = rgb/(2·max) (each in [0, ½], the largest ½): the
    /// trilinear blend of the lattice colours' about c, each uplifted once (cached), as weights over lattice spectra.
    /// </summary>
    public void UnitSpectrum(double r, double g, double b, Span<(TabulatedSpectrum Spectrum, double Weight)> blend)
    {
        Span<double> c = [r, g, b];
        Span<int> lo = stackalloc int[3];
        Span<double> t = stackalloc double[3];
        for (int k = 0; k < 3; k++)
        {
            double x = Math.Clamp(c[k], 0, 0.5) * LatticeSteps;
            lo[k] = Math.Min((int)Math.Floor(x), LatticeSteps / 2 - 1);
            t[k] = x - lo[k];
        }
        Span<int> at = stackalloc int[3];
        for (int corner = 0; corner < 8; corner++)
        {
            double w = 1;
            for (int k = 0; k < 3; k++)
            {
                int bit = (corner >> k) & 1;
                at[k] = lo[k] + bit;
                w *= bit == 1 ? t[k] : 1 - t[k];
            }
            blend[corner] = (w > 0 ? Corner(at[0], at[1], at[2]) : Corner(lo[0], lo[1], lo[2]), w);
        }
    }

    /// <summary>The unit spectrum of lattice colour (i, j, k)/<see cref="LatticeSteps"/>, uplifted exactly (cached).</summary>
    TabulatedSpectrum Corner(int i, int j, int k)
    {
        int key = (i * 9 + j) * 9 + k;
        lock (_lock) if (_corners.TryGetValue(key, out var s)) return s;
        var r = IlluminantUplift.Reflectance((double)i / LatticeSteps, (double)j / LatticeSteps, (double)k / LatticeSteps);
        var spectrum = IlluminantUplift.Product($"{Source} lattice ({i}, {j}, {k})", r, 1, _d65, _luminanceFactor);
        lock (_lock) _corners[key] = spectrum;
        return spectrum;
    }

    /// <summary>
    /// The mean radiance over the sphere of the pixels taken as constant over their cells' solid angles (rows weighted by
    /// ∫ sin θ over their half-rows), as one colour: what a uniform sky of the same light has (Whitted's background).
    /// </summary>
    public double[] MeanRgb()
    {
        double sr = 0, sg = 0, sb = 0, total = 0;
        for (int y = 0; y < Height; y++)
        {
            double w = RowSolidAngle(y);
            for (int x = 0; x < Width; x++)
            {
                int o = 3 * (y * Width + x);
                sr += w * Rgb[o]; sg += w * Rgb[o + 1]; sb += w * Rgb[o + 2];
                total += w;
            }
        }
        return [Scale * sr / total, Scale * sg / total, Scale * sb / total];
    }

    /// <summary>
    /// A pixel of row y's solid angle × W/2π: cos θ_a − cos θ_b over the row's band, from half a row above it to half a row
    /// below (rows at θ = πy/(H − 1)); for an equal-area square 2/N (4π/N² × N/2π). Over all rows they sum to 2.
    /// </summary>
    public double RowSolidAngle(int y)
    {
        if (Mapping == EnvironmentMapping.EqualArea) return 2.0 / Height;
        double step = Math.PI / (Height - 1);
        double a = Math.Max(0, (y - 0.5) * step), b = Math.Min(Math.PI, (y + 0.5) * step);
        return Math.Cos(a) - Math.Cos(b);
    }
}

/// <summary>The layout of an environment map's image (<see cref="EnvironmentMap"/>).</summary>
public enum EnvironmentMapping
{
    /// <summary>Equirectangular, Mitsuba 3's conventions (+Y up, pixels the vertices of a bilinear grid).</summary>
    LatLong,
    /// <summary>pbrt-v4's equal-area octahedral square (<see cref="EqualAreaSquare"/>, +Z at its centre, nearest pixel).</summary>
    EqualArea,
}
