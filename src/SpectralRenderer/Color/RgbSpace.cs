using System.Runtime.CompilerServices;
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
        return (Encode8(r), Encode8(g), Encode8(b));
    }

    /// <summary>The 8-bit code of a linear value, To8(Encode(linear)) exactly; the sRGB curve without pow (<see cref="Srgb8"/>).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public byte Encode8(double linear) => UsesSrgbCurve ? Srgb8.Table.Encode(linear) : To8(Encode(linear));

    public (ushort R, ushort G, ushort B) Encode16(Xyz xyz)
    {
        var (r, g, b) = Linear(xyz);
        return (To16(Encode(r)), To16(Encode(g)), To16(Encode(b)));
    }

    /// <summary>
    /// To8(SrgbCurve(c)) by table: the 8-bit code rises by one at 255 thresholds, each found once as the least double
    /// whose code the exact formula puts at k. A value's code is that of the lower edge of its 1/4096-wide bucket, plus
    /// one if it reaches the next threshold: the curve's slope is at most 12.92, so thresholds are ≥ 1/3295 apart and
    /// a bucket holds at most one (checked when the table is built). Instance fields, so callers pay no static-init checks.
    /// </summary>
    sealed class Srgb8
    {
        const int Buckets = 4096;          // a power of two: c · Buckets is exact, so bucket i is [i, i + 1) / Buckets
        readonly double[] _threshold;      // [k] = least c with code k, k = 1 … 255; [0] = −∞, [256] = +∞
        readonly byte[] _bucketCode;

        public static readonly Srgb8 Table = new();

        Srgb8()
        {
            _threshold = new double[257];
            _threshold[0] = double.NegativeInfinity;
            _threshold[256] = double.PositiveInfinity;
            for (int k = 1; k <= 255; k++)
            {
                // Start at the curve's inverse of the rounding midpoint (k − ½)/255, then step by ulps to the exact boundary.
                double m = (k - 0.5) / 255;
                double c = m <= 12.92 * 0.0031308 ? m / 12.92 : Math.Pow((m + 0.055) / 1.055, 2.4);
                while (c > 0 && To8(SrgbCurve(c)) >= k) c = Math.BitDecrement(c);
                while (To8(SrgbCurve(c)) < k) c = Math.BitIncrement(c);
                _threshold[k] = c;
            }
            _bucketCode = new byte[Buckets + 1];
            for (int i = 0, k = 0; i <= Buckets; i++)
            {
                double edge = i / (double)Buckets;
                while (k < 255 && _threshold[k + 1] <= edge) k++;
                _bucketCode[i] = (byte)k;
                if (i > 0 && _bucketCode[i] > _bucketCode[i - 1] + 1)
                    throw new InvalidOperationException("two sRGB code thresholds in one bucket");
            }
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public byte Encode(double linear)
        {
            if (!(linear > 0)) return 0;                    // negative, zero or NaN, as Encode clips them
            if (linear >= 1) return 255;
            int code = _bucketCode[(int)(linear * Buckets)];
            return (byte)(linear >= _threshold[code + 1] ? code + 1 : code);
        }
    }

    public static byte To8(double v) => (byte)Math.Round(255 * v, MidpointRounding.AwayFromZero);
    public static ushort To16(double v) => (ushort)Math.Round(65535 * v, MidpointRounding.AwayFromZero);
}
