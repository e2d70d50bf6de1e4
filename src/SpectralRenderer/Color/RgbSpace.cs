using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Color;

/// <summary>A display RGB space: the matrix from XYZ, its white, and its encoding curve.</summary>
public sealed class RgbSpace
{
    RgbSpace(string name, double[,] fromXyz, Xyz white, bool srgbCurve)
    {
        Name = name;
        FromXyz = fromXyz;
        White = white;
        UsesSrgbCurve = srgbCurve;
    }

    public string Name { get; }
    public double[,] FromXyz { get; }
    public Xyz White { get; }
    public bool UsesSrgbCurve { get; }

    /// <summary>sRGB, IEC 61966-2-1:1999: the standard's 4-decimal matrix (D65 white) and its transfer curve.</summary>
    public static RgbSpace Srgb { get; } = new("srgb", new double[,]
    {
        { 3.2406, -1.5372, -0.4986 },
        { -0.9689, 1.8758, 0.0415 },
        { 0.0557, -0.2040, 1.0570 },
    }, Xyz.D65White, true);

    /// <summary>The paper's eq. 4 (the NTSC 1953 RGB matrix, illuminant C white), linear and clipped.</summary>
    public static RgbSpace Paper { get; } = new("paper", new double[,]
    {
        { 1.910, -0.532, -0.288 },
        { -0.985, 1.999, -0.028 },
        { 0.058, -0.118, 0.898 },
    }, Xyz.CWhite, false);

    public static RgbSpace Parse(string name, string where = "--rgb") => name.ToLowerInvariant() switch
    {
        "srgb" => Srgb,
        "paper" => Paper,
        _ => throw new InputException(where, $"unknown RGB mode '{name}'", "use srgb or paper"),
    };

    /// <summary>Linear RGB = M·XYZ (unclipped).</summary>
    public (double R, double G, double B) Linear(Xyz xyz)
    {
        var v = Matrix3.Apply(FromXyz, xyz);
        return (v.X, v.Y, v.Z);
    }

    /// <summary>Display value in [0, 1]: clip, then the sRGB curve (or none for eq. 4).</summary>
    public double Encode(double linear)
    {
        double c = Math.Clamp(linear, 0, 1);
        if (double.IsNaN(linear)) c = 0;
        return UsesSrgbCurve ? SrgbCurve(c) : c;
    }

    /// <summary>The sRGB transfer function (IEC 61966-2-1 eq. 5).</summary>
    public static double SrgbCurve(double c) => c <= 0.0031308 ? 12.92 * c : 1.055 * Math.Pow(c, 1 / 2.4) - 0.055;

    /// <summary>8-bit code value: round(255 · encoded).</summary>
    public (byte R, byte G, byte B) Encode8(Xyz xyz)
    {
        var (r, g, b) = Linear(xyz);
        return (To8(Encode(r)), To8(Encode(g)), To8(Encode(b)));
    }

    public (ushort R, ushort G, ushort B) Encode16(Xyz xyz)
    {
        var (r, g, b) = Linear(xyz);
        return (To16(Encode(r)), To16(Encode(g)), To16(Encode(b)));
    }

    public static byte To8(double v) => (byte)Math.Round(255 * v, MidpointRounding.AwayFromZero);
    public static ushort To16(double v) => (ushort)Math.Round(65535 * v, MidpointRounding.AwayFromZero);
}
