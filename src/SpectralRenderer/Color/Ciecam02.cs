namespace SpectralRenderer.Color;

/// <summary>
/// The CIECAM02 colour appearance model, forward direction (CIE 159:2004), and the CAM02-UCS uniform space
/// of Luo, Cui &amp; Li (2006), as CIE 224:2017 uses them: XYZ and the adopted white on the scale Y_w = 100,
/// adapting luminance L_A, background Y_b, the surround's F, c, N_c, and a degree of adaptation D
/// (1 when the illuminant is discounted).
/// </summary>
public sealed class Ciecam02
{
    static readonly double[,] Cat02 = { { 0.7328, 0.4296, -0.1624 }, { -0.7036, 1.6975, 0.0061 }, { 0.0030, 0.0136, 0.9834 } };
    static readonly double[,] Hpe = { { 0.38971, 0.68898, -0.07868 }, { -0.22981, 1.18340, 0.04641 }, { 0.0, 0.0, 1.0 } };
    static readonly double[,] HpeFromCat02 = Matrix3.Multiply(Hpe, Matrix3.Inverse(Cat02));

    readonly Xyz _wRgb, _dRgb;
    readonly double _fl, _n, _nbb, _z, _c, _nc, _aw;

    /// <summary>Viewing conditions; "average" surround is F = 1, c = 0.69, N_c = 1.</summary>
    public Ciecam02(Xyz white, double adaptingLuminance, double backgroundY, double f = 1.0, double c = 0.69, double nc = 1.0,
        double? degreeOfAdaptation = null)
    {
        double la = adaptingLuminance;
        double d = degreeOfAdaptation ?? f * (1 - 1 / 3.6 * Math.Exp((-la - 42) / 92));
        _wRgb = Matrix3.Apply(Cat02, white);
        _dRgb = new Xyz(white.Y * d / _wRgb.X + 1 - d, white.Y * d / _wRgb.Y + 1 - d, white.Y * d / _wRgb.Z + 1 - d);
        double k = 1 / (5 * la + 1), k4 = k * k * k * k;
        _fl = 0.2 * k4 * 5 * la + 0.1 * (1 - k4) * (1 - k4) * Math.Cbrt(5 * la);
        _n = backgroundY / white.Y;
        _nbb = 0.725 * Math.Pow(1 / _n, 0.2);
        _z = 1.48 + Math.Sqrt(_n);
        _c = c; _nc = nc;
        var wa = PostAdaptation(white);
        _aw = Achromatic(wa);
    }

    /// <summary>Lightness J, colourfulness M and hue angle h (degrees) of a stimulus.</summary>
    public (double J, double M, double H) Appearance(Xyz xyz)
    {
        var ra = PostAdaptation(xyz);
        double a = ra.X - 12 * ra.Y / 11 + ra.Z / 11;
        double b = (ra.X + ra.Y - 2 * ra.Z) / 9;
        double h = Math.Atan2(b, a) * 180 / Math.PI;
        if (h < 0) h += 360;
        double et = 0.25 * (Math.Cos(h * Math.PI / 180 + 2) + 3.8);
        double j = 100 * Math.Pow(Achromatic(ra) / _aw, _c * _z);
        double t = 50000.0 / 13 * _nc * _nbb * et * Math.Sqrt(a * a + b * b) / (ra.X + ra.Y + 21.0 / 20 * ra.Z);
        double chroma = Math.Pow(t, 0.9) * Math.Sqrt(j / 100) * Math.Pow(1.64 - Math.Pow(0.29, _n), 0.73);
        return (j, chroma * Math.Pow(_fl, 0.25), h);
    }

    /// <summary>CAM02-UCS J′a′b′: J′ = 1.7J / (1 + 0.007J), M′ = ln(1 + 0.0228M) / 0.0228.</summary>
    public (double J, double A, double B) Ucs(Xyz xyz)
    {
        var (j, m, h) = Appearance(xyz);
        double mp = Math.Log(1 + 0.0228 * m) / 0.0228;
        return (1.7 * j / (1 + 0.007 * j), mp * Math.Cos(h * Math.PI / 180), mp * Math.Sin(h * Math.PI / 180));
    }

    Xyz PostAdaptation(Xyz xyz)
    {
        var rgb = Matrix3.Apply(Cat02, xyz);
        var rc = new Xyz(rgb.X * _dRgb.X, rgb.Y * _dRgb.Y, rgb.Z * _dRgb.Z);
        var p = Matrix3.Apply(HpeFromCat02, rc);
        return new Xyz(Compress(p.X), Compress(p.Y), Compress(p.Z));
    }

    double Compress(double x)
    {
        double f = Math.Pow(_fl * Math.Abs(x) / 100, 0.42);
        return Math.Sign(x) * 400 * f / (27.13 + f) + 0.1;
    }

    double Achromatic(Xyz ra) => (2 * ra.X + ra.Y + ra.Z / 20 - 0.305) * _nbb;
}
