using SpectralRenderer.Color;
using SpectralRenderer.Spectra;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Color;

public class ColorimetryTests(ITestOutputHelper output)
{
    static readonly TabulatedSpectrum D65 = SpectrumLibrary.Resolve("D65");

    [Fact]
    public void Ciede2000_reproduces_all_34_Sharma_pairs()
    {
        var rows = Reference.Rows("ciede2000-sharma-2005.csv");
        Assert.Equal(34, rows.Count);
        foreach (var r in rows)
        {
            var d = DeltaE2000.Between(new Lab(r.D("L1"), r.D("a1"), r.D("b1")), new Lab(r.D("L2"), r.D("a2"), r.D("b2")));
            Assert.True(Math.Abs(d - r.D("dE00")) <= 1e-4, $"pair {r["pair"]}: {d:F6} vs {r["dE00"]}");
            // symmetric
            Assert.Equal(d, DeltaE2000.Between(new Lab(r.D("L2"), r.D("a2"), r.D("b2")), new Lab(r.D("L1"), r.D("a1"), r.D("b1"))), 10);
        }
    }

    [Fact]
    public void Patches_at_1nm_match_the_reference_XYZ_Lab_and_8bit_sRGB()
    {
        var reference = new ReferenceColorimeter(Observer.Cie1931, D65);
        Assert.Equal(0.950423, reference.White.X, 6);
        Assert.Equal(1.088610, reference.White.Z, 6);
        var rows = Reference.Rows("colorchecker-ohta-d65-2deg.csv");
        Assert.Equal(24, rows.Count);
        for (int p = 1; p <= 24; p++)
        {
            var r = rows[p - 1];
            var xyz = reference.OfReflectance(ColorChecker.Patch(p));
            Assert.True(Math.Abs(xyz.X - r.D("X")) < 1e-6 && Math.Abs(xyz.Y - r.D("Y")) < 1e-6 && Math.Abs(xyz.Z - r.D("Z")) < 1e-6,
                $"patch {p}: {xyz} vs {r["X"]},{r["Y"]},{r["Z"]}");
            var lab = Lab.FromXyz(xyz, reference.White);
            Assert.True(Math.Abs(lab.L - r.D("L")) < 1e-6 && Math.Abs(lab.A - r.D("a")) < 1e-6 && Math.Abs(lab.B - r.D("b")) < 1e-6,
                $"patch {p} Lab {lab}");
            var (lr, lg, lb) = RgbSpace.Srgb.Linear(xyz);
            Assert.Equal(r.D("srgb_linear_r"), lr, 6);
            Assert.Equal(r.D("srgb_linear_g"), lg, 6);
            Assert.Equal(r.D("srgb_linear_b"), lb, 6);
            var rgb8 = RgbSpace.Srgb.Encode8(xyz);
            Assert.Equal(((int)r.D("srgb8_r"), (int)r.D("srgb8_g"), (int)r.D("srgb8_b")), ((int)rgb8.R, (int)rgb8.G, (int)rgb8.B));
            // 16-bit: the same encoded value at 65535 levels, within half a step of 257 × the 8-bit code.
            var rgb16 = RgbSpace.Srgb.Encode16(xyz);
            Assert.Equal(RgbSpace.To16(RgbSpace.Srgb.Encode(lr)), rgb16.R);
            Assert.InRange(rgb16.G / 257.0, rgb8.G - 0.5, rgb8.G + 0.5);
        }
    }

    [Fact]
    public void Paper_scheme_with_20_bands_matches_the_reference()
    {
        var c = new Colorimeter(BandGrid.Default, Observer.Cie1931, D65, BandIntegration.Paper);
        Assert.Equal(1.0, c.White.Y, 12);
        var reference = new ReferenceColorimeter(Observer.Cie1931, D65);
        var rows = Reference.Rows("colorchecker-ohta-d65-2deg-bands20.csv");
        for (int p = 1; p <= 24; p++)
        {
            var r = rows[p - 1];
            var xyz = c.OfReflectance(ColorChecker.Patch(p));
            Assert.True(Math.Abs(xyz.X - r.D("X")) < 1e-6 && Math.Abs(xyz.Y - r.D("Y")) < 1e-6 && Math.Abs(xyz.Z - r.D("Z")) < 1e-6,
                $"patch {p}: {xyz}");
            var de = DeltaE2000.Between(Lab.FromXyz(xyz, reference.White),
                Lab.FromXyz(reference.OfReflectance(ColorChecker.Patch(p)), reference.White));
            Assert.Equal(r.D("dE00_vs_1nm"), de, 4);
        }
    }

    [Theory]
    [InlineData("D65")]
    [InlineData("A")]
    [InlineData("FL11")]
    [InlineData("led-blue")]
    [InlineData("led-green")]
    public void Default_scheme_with_20_bands_meets_the_bar_against_1nm(string light)
    {
        var (mean, max) = PatchErrors(light, BandIntegration.Weighted, BandGrid.Default);
        output.WriteLine($"{light}: mean {mean:F3} max {max:F3}");
        Assert.True(mean <= 0.6 && max <= 1.6, $"{light}: mean ΔE00 {mean:F3}, max {max:F3}");
    }

    [Theory]
    [InlineData("led-blue", 4.0)]
    [InlineData("led-green", 4.0)]
    public void Paper_scheme_is_far_off_for_narrow_band_LEDs(string light, double atLeastMean)
    {
        // The guide's diagnosis: the mean of a product is not the product of the means.
        var (mean, _) = PatchErrors(light, BandIntegration.Paper, BandGrid.Default);
        output.WriteLine($"paper {light}: {mean:F3}");
        Assert.True(mean >= atLeastMean, $"{light}: paper scheme mean ΔE00 {mean:F2}");
    }

    [Fact]
    public void Weighted_scheme_with_80_bands_is_within_0_05_under_D65()
    {
        var (_, max) = PatchErrors("D65", BandIntegration.Weighted, new BandGrid(380, 780, 80));
        Assert.True(max < 0.05, $"max ΔE00 {max:F4}");
    }

    internal static (double Mean, double Max) PatchErrors(string light, BandIntegration scheme, BandGrid grid)
    {
        var e = SpectrumLibrary.Resolve(light);
        var reference = new ReferenceColorimeter(Observer.Cie1931, e);
        var c = new Colorimeter(grid, Observer.Cie1931, e, scheme);
        double sum = 0, max = 0;
        for (int p = 1; p <= 24; p++)
        {
            var patch = ColorChecker.Patch(p);
            double d = DeltaE2000.Between(Lab.FromXyz(c.OfReflectance(patch), reference.White),
                Lab.FromXyz(reference.OfReflectance(patch), reference.White));
            sum += d; max = Math.Max(max, d);
        }
        return (sum / 24, max);
    }

    [Fact]
    public void Bradford_maps_white_to_white_and_matches_the_published_D65_to_D50_matrix()
    {
        var d50 = new Xyz(0.96422, 1.0, 0.82521);
        var m = ChromaticAdaptation.BradfordMatrix(Xyz.D65White, d50);
        var w = Matrix3.Apply(m, Xyz.D65White);
        Assert.Equal(d50.X, w.X, 12); Assert.Equal(d50.Z, w.Z, 12);
        // Lindbloom's Bradford D65→D50 matrix, first row: 1.0478112 0.0228866 -0.0501270
        Assert.Equal(1.0478112, m[0, 0], 5); Assert.Equal(0.0228866, m[0, 1], 5); Assert.Equal(-0.0501270, m[0, 2], 5);
    }

    [Fact]
    public void Absolute_scaling_uses_683_lm_per_W()
    {
        var c = new Colorimeter(BandGrid.Default, Observer.Cie1931, D65, absolute: true);
        Assert.Equal(683.0, c.Kappa);
        // Y of the white = 683 Σ ȳ E at 1 nm (CIE 015 §7.1, trapezoidal form).
        double y = 683 * Cie015.Sum(l => Observer.Cie1931.YBar.Evaluate(l) * D65.Evaluate(l));
        Assert.Equal(1, c.White.Y / y, 12);
    }

    [Fact]
    public void Ten_degree_observer_white_is_the_D65_10deg_white_point()
    {
        var r = new ReferenceColorimeter(Observer.Cie1964, D65);
        // CIE 015:2018 Table 11.3 (D65, 10°, 1 nm over 380–780): X = 94.81, Z = 107.32
        Assert.Equal(0.9481, r.White.X, 3);
        Assert.Equal(1.0732, r.White.Z, 3);
    }
}
