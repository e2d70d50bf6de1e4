using System.Numerics;
using SpectralRenderer.Validation;

namespace SpectralRenderer.Tests.Validation;

/// <summary>
/// The closed forms of the CIE overcast sky cases (<see cref="Closed"/>) against a second method: Gauss–Legendre quadrature
/// of L(θ)·cos dω written here, over the sky's hemisphere in (θ, φ), or over an opening's area (dω = cos_A·dA/r²); and the
/// openings' uniform-sky forms against Lambert's polygon formula.
/// </summary>
public class OvercastReferenceTests
{
    /// <summary>(1 + 2 cos θ)/3 above the horizon, 0 below (CIE S 011 type 1, traditional form).</summary>
    static double G(double mu) => mu > 0 ? (1 + 2 * mu) / 3 : 0;

    /// <summary>∫∫ f over [a0, a1] × [b0, b1]: composite Gauss–Legendre, 16 panels of 16 points per axis.</summary>
    static double Quad2(Func<double, double, double> f, double a0, double a1, double b0, double b1)
    {
        const int panels = 16;
        double sum = 0;
        for (int i = 0; i < panels; i++)
        {
            var (x, wx) = Closed.GaussLegendre(16, a0 + (a1 - a0) * i / panels, a0 + (a1 - a0) * (i + 1) / panels);
            for (int j = 0; j < panels; j++)
            {
                var (y, wy) = Closed.GaussLegendre(16, b0 + (b1 - b0) * j / panels, b0 + (b1 - b0) * (j + 1) / panels);
                for (int p = 0; p < x.Length; p++)
                    for (int q = 0; q < y.Length; q++) sum += wx[p] * wy[q] * f(x[p], y[q]);
            }
        }
        return sum;
    }

    [Fact]
    public void Horizontal_and_vertical_illuminance_are_the_quadrature_of_the_sky()
    {
        // θ from the zenith (y), φ about it; dω = sin θ dθ dφ. Horizontal: cos = cos θ.
        double horizontal = Quad2((t, p) => G(Math.Cos(t)) * Math.Cos(t) * Math.Sin(t), 0, Math.PI / 2, 0, 2 * Math.PI);
        Assert.Equal(7 * Math.PI / 9, horizontal, 1e-12);
        Assert.Equal(Closed.OvercastHorizontal, horizontal, 1e-12);
        // Vertical, normal along φ = 0: cos = sin θ cos φ, the sky in front of the plane φ ∈ [−π/2, π/2].
        double vertical = Quad2((t, p) => G(Math.Cos(t)) * Math.Sin(t) * Math.Cos(p) * Math.Sin(t), 0, Math.PI / 2,
            -Math.PI / 2, Math.PI / 2);
        Assert.Equal(Closed.OvercastVertical, vertical, 1e-12);
        Assert.Equal(0.968, Closed.OvercastVertical, 1e-3);   // π/6 + 4/9 = 0.96804…
    }

    // The validation's room: receivers on the floor (y = 0) facing up; the roof opening x, z ∈ [−1.5, 1.5] at y = 2; the
    // window x ∈ [−1.5, 1.5], y ∈ [0.5, 1.75] in the wall z = −3.
    public static TheoryData<float, float> Points() =>
        new() { { 0, 0.4f }, { 1.25f, 0.4f }, { 2.5f, 0.4f }, { 2.9f, -2.75f }, { -0.3f, 1 } };

    [Theory, MemberData(nameof(Points))]
    public void The_roof_openings_closed_form_is_the_quadrature_over_its_area(float x, float z)
    {
        const double h = 2;
        // From (x, 0, z) to (u, h, v): r² = (u − x)² + h² + (v − z)²; μ = cos_receiver = cos_A = h/r.
        double Integrand(double u, double v, bool overcast)
        {
            double r = Math.Sqrt((u - x) * (u - x) + h * h + (v - z) * (v - z)), mu = h / r;
            return (overcast ? G(mu) : 1) * mu * mu / (r * r);
        }
        double overcast = Quad2((u, v) => Integrand(u, v, true), -1.5, 1.5, -1.5, 1.5);
        Assert.Equal(overcast, Closed.OvercastRoof(h, -1.5 - x, 1.5 - x, -1.5 - z, 1.5 - z), 1e-10);
        double uniform = Quad2((u, v) => Integrand(u, v, false), -1.5, 1.5, -1.5, 1.5);
        var opening = Closed.Rectangle(new Vector3(0, 2, 0), Vector3.UnitX, Vector3.UnitZ, 3, 3);
        Assert.Equal(uniform, Closed.ProjectedSolidAngle(new Vector3(x, 0, z), Vector3.UnitY, opening), 1e-6);
    }

    [Theory, MemberData(nameof(Points))]
    public void The_windows_form_is_the_quadrature_over_its_area(float x, float z)
    {
        double d = z + 3;
        // From (x, 0, z) to (u, w, −3): r² = (u − x)² + w² + d²; μ = cos_receiver = w/r, cos_A = d/r.
        double Integrand(double u, double w, bool overcast)
        {
            double r = Math.Sqrt((u - x) * (u - x) + w * w + d * d), mu = w / r;
            return (overcast ? G(mu) : 1) * mu * (d / r) / (r * r);
        }
        double overcast = Quad2((u, w) => Integrand(u, w, true), -1.5, 1.5, 0.5, 1.75);
        Assert.Equal(overcast, Closed.SkyWindow(d, -1.5 - x, 1.5 - x, 0.5, 1.75, overcast: true), 1e-10);
        double uniform = Quad2((u, w) => Integrand(u, w, false), -1.5, 1.5, 0.5, 1.75);
        Assert.Equal(uniform, Closed.SkyWindow(d, -1.5 - x, 1.5 - x, 0.5, 1.75, overcast: false), 1e-10);
        var window = Closed.Rectangle(new Vector3(0, 1.125f, -3), Vector3.UnitX, Vector3.UnitY, 3, 1.25);
        Assert.Equal(uniform, Closed.ProjectedSolidAngle(new Vector3(x, 0, z), Vector3.UnitY, window), 1e-6);
    }
}
