using System.Numerics;

namespace SpectralRenderer.Validation;

/// <summary>
/// The closed forms the cases compare against, in double precision and written from their sources, independent of the
/// engine's code: Lambert's polygon formula for the projected solid angle (form factors of area sources and sky
/// openings), Gauss–Legendre quadrature (the closed surfaces' flux), and the photometric frame of a type C luminaire.
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
