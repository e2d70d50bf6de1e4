namespace SpectralRenderer.Color;

/// <summary>CIE XYZ tristimulus values.</summary>
public readonly record struct Xyz(double X, double Y, double Z)
{
    public static Xyz operator *(Xyz a, double s) => new(a.X * s, a.Y * s, a.Z * s);
    public static Xyz operator +(Xyz a, Xyz b) => new(a.X + b.X, a.Y + b.Y, a.Z + b.Z);
    /// <summary>CIE illuminant D65 white, Y = 1 (the sRGB reference white, IEC 61966-2-1).</summary>
    public static Xyz D65White => new(0.95047, 1.0, 1.08883);
    /// <summary>CIE illuminant C white, Y = 1 (the white of NTSC 1953 and of the paper's eq. 4).</summary>
    public static Xyz CWhite => new(0.98074, 1.0, 1.18232);
}
