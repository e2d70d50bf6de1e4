using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Color;

/// <summary>CIE 13.3 Ra and CIE 224:2017 Rf against data/reference/colour-rendering.csv (colour-science 0.4.7).</summary>
public class ColorRenderingTests
{
    static readonly Dictionary<string, string> Names = new()
    {
        ["A"] = "A",
        ["D65"] = "D65",
        ["FL2"] = "FL2",
        ["FL11"] = "FL11",
        ["3-LED-1 (457/540/605)"] = "led-rgb",
        ["Phosphor LED YAG"] = "led-yag",
    };

    public static TheoryData<string> Sources() => new(Names.Keys);

    [Theory, MemberData(nameof(Sources))]
    public void Ra_and_Rf_match_the_reference_within_0_1(string column)
    {
        var row = Reference.Rows("colour-rendering.csv").Single(r => r["column"] == column);
        var light = SpectrumLibrary.Resolve(Names[column]);
        var ra = ColorRenderingIndex.Of(light);
        var rf = ColorFidelityIndex.Of(light);
        Assert.InRange(ra.Ra, row.D("Ra_CIE13.3") - 0.1, row.D("Ra_CIE13.3") + 0.1);
        Assert.InRange(rf.Rf, row.D("Rf_CIE224_2017") - 0.1, row.D("Rf_CIE224_2017") + 0.1);
    }

    [Fact]
    public void Cct_of_the_CIE_illuminants_is_their_nominal_temperature()
    {
        // CIE 015:2018 Table 2: A 2856 K, D65 6504 K (D65's nominal 6500 K on the older c2).
        Assert.InRange(CorrelatedColorTemperature.Of(SpectrumLibrary.Resolve("A")).Kelvin, 2855, 2857);
        Assert.InRange(CorrelatedColorTemperature.Of(SpectrumLibrary.Resolve("D65")).Kelvin, 6500, 6508);
        // A blackbody is on the locus: its CCT is its temperature and Δuv is 0.
        var (t, duv) = CorrelatedColorTemperature.Of(Planck.Spectrum(3000));
        Assert.InRange(t, 2999.9, 3000.1);
        Assert.InRange(duv, -1e-6, 1e-6);
    }
}

/// <summary>blackbody:T and daylight:T against the CIE tables they must reproduce.</summary>
public class IlluminantSpectraTests
{
    [Fact]
    public void Blackbody_reproduces_illuminant_A()
    {
        // CIE A is Planck's law with c2 = 1.435e-2 m·K at 2848 K, i.e. 2848·c2/1.435e-2 K on the current c2.
        var a = SpectrumLibrary.Resolve("A");
        var bb = SpectrumLibrary.Resolve("blackbody:"
            + (2848 * Planck.C2 / 1.435e7).ToString(System.Globalization.CultureInfo.InvariantCulture));
        for (int l = 380; l <= 780; l += 5)
            Assert.Equal(a.Evaluate(l), bb.Evaluate(l), a.Evaluate(l) * 2e-5);
        Assert.Equal(100, SpectrumLibrary.Resolve("blackbody:5000").Evaluate(560), 1e-12);
    }

    [Fact]
    public void Blackbody_peaks_where_Wien_says()
    {
        // Wien's displacement law: λ_max = b / T, b = 2.897771955e6 nm·K.
        var bb = Planck.Spectrum(5000);
        int peak = Enumerable.Range(300, 531).MaxBy(l => bb.Evaluate(l));
        Assert.InRange(peak, 579, 580);
    }

    [Theory]
    [InlineData("D65", 6504.0)]
    [InlineData("D50", 5003.0)]
    public void Daylight_reproduces_the_CIE_tables(string name, double kelvin)
    {
        // The CIE tabulated D65 and D50 from S0 + M1 S1 + M2 S2 at their chromaticity; from the CCT on the
        // current c2 (6504 K, 5003 K) with M1, M2 rounded to 3 decimals the same SPD follows within 0.1 %.
        var table = SpectrumLibrary.Resolve(name);
        var d = SpectrumLibrary.Resolve($"daylight:{kelvin}");
        for (int l = 380; l <= 780; l += 5)
            Assert.Equal(table.Evaluate(l), d.Evaluate(l), table.Evaluate(l) * 1e-3);
    }

    [Theory]
    [InlineData("blackbody:hot", "blackbody:")]
    [InlineData("blackbody:-5", "blackbody:")]
    [InlineData("daylight:3000", "4000 and 25000")]
    [InlineData("daylight:", "daylight:")]
    public void Bad_temperatures_are_one_line_errors(string name, string says)
    {
        var e = Assert.Throws<InputException>(() => SpectrumLibrary.Resolve(name, where: "lights[0].spectrum"));
        Assert.Contains(says, e.Message);
        Assert.StartsWith("lights[0].spectrum:", e.Message);
        Assert.DoesNotContain('\n', e.Message);
    }
}

/// <summary>Sprague interpolation reproduces a quartic exactly (its derivative estimates are fourth-order) and passes through the
/// samples.</summary>
public class SpragueTests
{
    [Fact]
    public void Sprague_is_exact_for_polynomials_up_to_degree_four()
    {
        static double P(double x) { double t = (x - 500) / 100; return 3 + t - 2 * t * t + 0.5 * t * t * t * t; }
        var w = Enumerable.Range(0, 41).Select(i => 400.0 + 5 * i).ToArray();
        var s = new TabulatedSpectrum("p", w, w.Select(P).ToArray());
        var r = Sprague.At1nm(s, 400, 600);
        // Exact where all six samples are tabulated (the boundary extrapolation is smooth, not polynomial).
        for (int l = 410; l <= 590; l++) Assert.Equal(P(l), r[l - 400], 1e-9);
        for (int l = 400; l <= 600; l += 5) Assert.Equal(P(l), r[l - 400], 1e-12);
    }
}
