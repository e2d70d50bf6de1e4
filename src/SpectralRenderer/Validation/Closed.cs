using System.Numerics;

namespace SpectralRenderer.Validation;

/// <summary>
/// The closed forms the cases compare against, in double precision and written from their sources, independent of the
/// engine's code: Lambert's polygon formula for the projected solid angle (form factors of area sources and sky
/// openings), the CIE overcast sky's illuminances on planes and through openings, Gauss–Legendre quadrature (the closed
/// surfaces' flux), and the photometric frame of a type C luminaire.
/// </summary>
internal static class Closed
{
    /// <summary>
    /// ∫ cos θ dω of a planar polygon seen from p with unit normal n (the polygon wholly in front of p's tangent plane):
    /// ½ |Σ_i Γ_i · n·(v_i × v_{i+1})/|v_i × v_{i+1}||, v_i the unit directions to the vertices and Γ_i the angle between
    /// consecutive ones — Lambert's polygon formula (Photometria, 1760); the configuration factor from a differential area
    /// to a polygon is this/π (its contour-integral form in Howell, Mengüç &amp; Siegel, Thermal Radiation Heat Transfer).
    /// A Lambertian source of luminance L gives E = L·∫cos θ dω; a uniform sky seen through an opening, the same.
    /// </summary>
    internal static double ProjectedSolidAngle(Vector3 p, Vector3 n, IReadOnlyList<Vector3> polygon)
    {
        double sum = 0;
        for (int i = 0; i < polygon.Count; i++)
        {
            var a = Unit(polygon[i], p);
            var b = Unit(polygon[(i + 1) % polygon.Count], p);
            double dot = Math.Clamp(a.X * b.X + a.Y * b.Y + a.Z * b.Z, -1, 1);
            double cx = a.Y * b.Z - a.Z * b.Y, cy = a.Z * b.X - a.X * b.Z, cz = a.X * b.Y - a.Y * b.X;
            double len = Math.Sqrt(cx * cx + cy * cy + cz * cz);
            if (len > 0) sum += Math.Acos(dot) * (n.X * cx + n.Y * cy + n.Z * cz) / len;
        }
        return Math.Abs(sum) / 2;
    }

    static (double X, double Y, double Z) Unit(Vector3 v, Vector3 p)
    {
        double x = (double)v.X - p.X, y = (double)v.Y - p.Y, z = (double)v.Z - p.Z, l = Math.Sqrt(x * x + y * y + z * z);
        return (x / l, y / l, z / l);
    }

    /// <summary>
    /// The CIE standard overcast sky's gradation L(θ)/L_z = (1 + 2 cos θ)/3 above the horizon, 0 below (Moon &amp; Spencer,
    /// Illuminating Engineering 37, 1942; CIE S 011/E:2003 sky type 1 in its traditional form), θ from the zenith.
    /// </summary>
    internal static double Overcast(double cosZenith) => cosZenith > 0 ? (1 + 2 * cosZenith) / 3 : 0;

    /// <summary>
    /// E_h/L_z on the open ground under the overcast sky: (1/3)∫₀^{2π}∫₀¹ (1 + 2μ)·μ dμ dφ = (2π/3)(1/2 + 2/3) = 7π/9.
    /// </summary>
    internal const double OvercastHorizontal = 7 * Math.PI / 9;

    /// <summary>
    /// E_v/L_z on a vertical plane (black ground): with θ from the zenith and φ from the plane's normal, cos = sin θ cos φ,
    /// (1/3)∫_{−π/2}^{π/2} cos φ dφ ∫₀^{π/2} (1 + 2 cos θ) sin²θ dθ = (2/3)(π/4 + 2/3) = π/6 + 4/9.
    /// </summary>
    internal const double OvercastVertical = Math.PI / 6 + 4.0 / 9;

    /// <summary>
    /// E/L_z at a point facing up under the overcast sky through a horizontal opening x ∈ [x0, x1], z ∈ [z0, z1] (relative
    /// to the point) at height h above it: the opening's points at distance r are seen at μ = h/r with dω = μ·dA/r², so
    /// E/L_z = (1/3)∫∫ (h²/r⁴ + 2h³/r⁵) dA, summed over the four corner rectangles with signs (each term even in x and z).
    /// Over [0, a] × [0, b]: ∫∫ h²/r⁴ dA = ½[a/√(a²+h²)·atan(b/√(a²+h²)) + b/√(b²+h²)·atan(a/√(b²+h²))] (π × the
    /// configuration factor to a parallel rectangle), and with Ω(h) = atan(ab/(hR)), R = √(a²+b²+h²), the solid angle
    /// (∫∫ h/r³ dA), ∫∫ h³/r⁵ dA = −(h²/3)·d(Ω/h)/dh = [Ω + h·ab(a²+b²+2h²)/(R(a²+h²)(b²+h²))]/3.
    /// </summary>
    internal static double OvercastRoof(double h, double x0, double x1, double z0, double z1) =>
        (Corner(x1, z1, h) - Corner(x0, z1, h) - Corner(x1, z0, h) + Corner(x0, z0, h)) / 3;

    /// <summary>The roof opening's ∫∫ (h²/r⁴ + 2h³/r⁵) dA over [0, a] × [0, b], odd in a and in b.</summary>
    static double Corner(double a, double b, double h)
    {
        double sign = Math.Sign(a) * Math.Sign(b);
        a = Math.Abs(a);
        b = Math.Abs(b);
        if (a == 0 || b == 0) return 0;
        double ah = Math.Sqrt(a * a + h * h), bh = Math.Sqrt(b * b + h * h), r = Math.Sqrt(a * a + b * b + h * h);
        double parallel = 0.5 * (a / ah * Math.Atan(b / ah) + b / bh * Math.Atan(a / bh));
        double omega = Math.Atan(a * b / (h * r));
        double cubed = (omega + h * a * b * (a * a + b * b + 2 * h * h) / (r * ah * ah * bh * bh)) / 3;
        return sign * (parallel + 2 * cubed);
    }

    /// <summary>
    /// E/L_z at a point facing up under the overcast sky (or a uniform sky, <paramref name="overcast"/> false: E/L) through a
    /// vertical opening in a wall at distance d in front of it, x ∈ [x0, x1] along the wall from the foot of the perpendicular
    /// and heights y ∈ [y0, y1] above the point (y0 ≥ 0). In the azimuth φ from the wall's normal and the elevation α,
    /// dω = cos α dα dφ, the receiver's cosine and the sky's cos θ are both s = sin α, and the opening spans φ ∈ [atan(x0/d),
    /// atan(x1/d)], s from s(y0) to s(y1), s(y) = y·cos φ/√(d² + y²cos²φ); the inner integral is exact,
    /// ∫ (1 + 2s)/3 · s ds = (s²/2 + 2s³/3)/3 (uniform: s²/2), the outer by 64-point Gauss–Legendre (a smooth integrand).
    /// </summary>
    internal static double SkyWindow(double d, double x0, double x1, double y0, double y1, bool overcast)
    {
        double Inner(double s) => overcast ? (s * s / 2 + 2 * s * s * s / 3) / 3 : s * s / 2;
        double S(double y, double c) => y * c / Math.Sqrt(d * d + y * y * c * c);
        var (phi, w) = GaussLegendre(64, Math.Atan(x0 / d), Math.Atan(x1 / d));
        double sum = 0;
        for (int i = 0; i < phi.Length; i++)
        {
            double c = Math.Cos(phi[i]);
            sum += w[i] * (Inner(S(y1, c)) - Inner(S(y0, c)));
        }
        return sum;
    }

    /// <summary>The four corners of a rectangle (centre, width along <paramref name="right"/>, height along
    /// <paramref name="up"/>), in order around it.</summary>
    internal static Vector3[] Rectangle(Vector3 centre, Vector3 right, Vector3 up, double width, double height)
    {
        var r = right * (float)(width / 2);
        var u = up * (float)(height / 2);
        return [centre - r - u, centre + r - u, centre + r + u, centre - r + u];
    }

    /// <summary>The n-point Gauss–Legendre nodes and weights on [a, b] (Newton's iteration on P_n; Abramowitz &amp; Stegun
    /// 25.4.29).</summary>
    internal static (double[] X, double[] W) GaussLegendre(int n, double a, double b)
    {
        var x = new double[n];
        var w = new double[n];
        for (int i = 0; i < n; i++)
        {
            double z = Math.Cos(Math.PI * (i + 0.75) / (n + 0.5)), dp = 0;
            for (int it = 0; it < 100; it++)
            {
                double p0 = 1, p1 = 0;
                for (int j = 1; j <= n; j++) { double p2 = p1; p1 = p0; p0 = ((2 * j - 1) * z * p1 - (j - 1) * p2) / j; }
                dp = n * (z * p0 - p1) / (z * z - 1);
                double dz = p0 / dp;
                z -= dz;
                if (Math.Abs(dz) < 1e-15) break;
            }
            x[i] = 0.5 * (a + b) + 0.5 * (b - a) * z;
            w[i] = (b - a) / ((1 - z * z) * dp * dp);
        }
        return (x, w);
    }

    /// <summary>The type C photometric frame as docs/scene-format.md states it: γ from the nadir (−y), C = 0 towards +x,
    /// C = 90° towards −z.</summary>
    internal static Vector3 TypeC(double cDegrees, double gammaDegrees)
    {
        double c = cDegrees * Math.PI / 180, g = gammaDegrees * Math.PI / 180;
        return new Vector3((float)(Math.Sin(g) * Math.Cos(c)), (float)-Math.Cos(g), (float)(-Math.Sin(g) * Math.Sin(c)));
    }

    /// <summary>An angle's label, "12.5°".</summary>
    internal static string Deg(double d) => $"{d.ToString("0.##", System.Globalization.CultureInfo.InvariantCulture)}°";
}
