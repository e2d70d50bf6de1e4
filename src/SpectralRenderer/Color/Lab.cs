namespace SpectralRenderer.Color;

/// <summary>CIE 1976 L*a*b* (CIE 015:2018 §8.2.1).</summary>
public readonly record struct Lab(double L, double A, double B)
{
    const double Epsilon = 216.0 / 24389.0;  // (6/29)^3
    const double Kappa = 24389.0 / 27.0;     // (29/3)^3

    public static Lab FromXyz(Xyz c, Xyz white)
    {
        double fx = F(c.X / white.X), fy = F(c.Y / white.Y), fz = F(c.Z / white.Z);
        return new Lab(116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz));
    }

    static double F(double t) => t > Epsilon ? Math.Cbrt(t) : (Kappa * t + 16) / 116;

    public double Chroma => Math.Sqrt(A * A + B * B);
}
