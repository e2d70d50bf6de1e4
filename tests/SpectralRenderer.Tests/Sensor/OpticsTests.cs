using System.Globalization;
using System.Numerics;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Scenes;
using SpectralRenderer.Sensor;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Sensor;

/// <summary>
/// The lens (issue 24): cos⁴ fall-off against the render camera's ray angles, the Airy pattern against its closed forms
/// (Bessel functions by their integral, the first zero at 1.2197·λN, the energy 1 − J₀² − J₁²), a blurred edge against the
/// edge response of the diffraction-limited OTF (Goodman), and a transmittance spectrum against a 0.1 nm integral.
/// </summary>
public class OpticsTests
{
    /// <summary>J_n(x) = (1/π)∫₀^π cos(nτ − x sin τ) dτ by the trapezoid rule on 4000 steps (a periodic integrand: spectrally
    /// accurate).</summary>
    static double BesselByIntegral(int n, double x)
    {
        const int M = 4000;
        double s = 0;
        for (int i = 0; i <= M; i++)
        {
            double tau = Math.PI * i / M, f = Math.Cos(n * tau - x * Math.Sin(tau));
            s += i == 0 || i == M ? f / 2 : f;
        }
        return s / M;
    }

    [Fact]
    public void Bessel_EqualsItsIntegralRepresentation_OnBothSidesOfTheSeriesSwitch()
    {
        foreach (double x in new[] { 0.0, 0.5, 1, 3.8317, 7, 11.99, 12, 12.01, 20, 37.5, 80 })
            foreach (int n in new[] { 0, 1 })
                Assert.True(Math.Abs(Optics.BesselJ(n, x) - BesselByIntegral(n, x)) < 1e-10,
                    $"J{n}({x}): {Optics.BesselJ(n, x)} vs {BesselByIntegral(n, x)}");
    }

    [Theory]
    [InlineData(450, 4)]
    [InlineData(700, 2.8)]
    public void Airy_FirstZeroAt1Point22LambdaN_AndItsEnergyIsOne(double lambda, double n)
    {
        // The first zero of J₁ is 3.8317059702075 (DLMF table 10.21.1): r₀ = 3.8317/π·λN = 1.2197·λN.
        double ln = lambda * 1e-3 * n, r0 = 3.8317059702075125 / Math.PI * ln;
        Assert.Equal(1.2197, r0 / ln, 4);
        double lo = 0.9 * r0, hi = 1.1 * r0;   // the minimum of the intensity by golden section
        for (int i = 0; i < 200; i++)
        {
            double a = lo + 0.382 * (hi - lo), b = lo + 0.618 * (hi - lo);
            if (Optics.Airy(a, lambda, n) < Optics.Airy(b, lambda, n)) hi = b; else lo = a;
        }
        Assert.True(Math.Abs(0.5 * (lo + hi) - r0) < 1e-4 * ln, $"first zero at {0.5 * (lo + hi) / ln} λN");
        Assert.True(Optics.Airy(r0, lambda, n) < 1e-12 * Optics.Airy(0, lambda, n));
        // ∫₀^R PSF·2πr dr by Simpson against the encircled energy 1 − J₀²(v) − J₁²(v); the peak is π/(4(λN)²).
        Assert.Equal(Math.PI / (4 * ln * ln), Optics.Airy(0, lambda, n), 9);
        foreach (double k in new[] { 1.0, 3, 10, 40 })
        {
            double r = k * ln, sum = 0;
            int m = 20000;
            for (int i = 0; i <= m; i++)
            {
                double x = r * i / m, f = Optics.Airy(x, lambda, n) * 2 * Math.PI * x;
                sum += (i == 0 || i == m ? 1 : i % 2 == 1 ? 4 : 2) * f;
            }
            sum *= r / m / 3;
            double v = Math.PI * k, j0 = BesselByIntegral(0, v), j1 = BesselByIntegral(1, v);
            Assert.True(Math.Abs(sum - (1 - j0 * j0 - j1 * j1)) < 1e-7, $"energy within {k} λN: {sum} vs {1 - j0 * j0 - j1 * j1}");
        }
        // The whole pattern: 1 − 2/(πv) → 1 as the radius grows (Rayleigh's asymptote of the encircled energy).
        Assert.InRange(Optics.EncircledEnergy(2000 * ln, lambda, n), 1 - 2.2 / (Math.PI * Math.PI * 2000),
            1 - 1.8 / (Math.PI * Math.PI * 2000));
    }

    [Fact]
    public void Kernel_SumsToOne_HoldsTheStatedEnergy_AndIsSymmetric()
    {
        var k = Optics.AiryKernel(550, 4, 2.8);
        Assert.Equal(1, k.Weights.Sum(), 12);
        Assert.InRange(k.CapturedEnergy, Optics.PsfEnergy, 1);
        for (int dy = -k.Radius; dy <= k.Radius; dy++)
            for (int dx = -k.Radius; dx <= k.Radius; dx++)
            {
                Assert.Equal(k[dx, dy], k[-dx, dy], 14);
                Assert.Equal(k[dx, dy], k[dy, dx], 14);
            }
        // The radius reaches where the encircled energy passes the target.
        Assert.True(Optics.EncircledEnergy(k.Radius * 2.8, 550, 4) >= Optics.PsfEnergy - 0.01);
    }

    /// <summary>
    /// A step edge at a pixel boundary blurred by the kernel against the same edge through the diffraction-limited OTF of a
    /// circular pupil, H(ν) = (2/π)[acos(ν/ν_c) − (ν/ν_c)√(1 − (ν/ν_c)²)], ν_c = 1/(λN) (Goodman, §6.3.2), and the
    /// photosite's box, sinc(νp): the pixel at x from the edge reads ½ + (1/π)∫₀^ν_c H(ν)·sinc(νp)·sin(2πνx)/ν dν.
    /// With the kernel cut at 99 % of the energy the two agree to 4e-3 of the step; at the default 97 %, to 1e-2.
    /// </summary>
    [Theory]
    [InlineData(0.99, 4e-3)]
    [InlineData(Optics.PsfEnergy, 1e-2)]
    public void BlurredEdge_MatchesTheEdgeResponseOfTheDiffractionOtf(double energy, double tolerance)
    {
        const double Lambda = 550, N = 4, P = 2.8;
        const int W = 48, H = 3;
        var kernel = Optics.AiryKernel(Lambda, N, P, energy);
        var data = new float[W * H];
        for (int y = 0; y < H; y++) for (int x = W / 2; x < W; x++) data[y * W + x] = 1;
        Optics.Apply(data, W, H, 1, null, [kernel]);
        double nuC = 1 / (Lambda * 1e-3 * N), worst = 0;
        for (int x = W / 2 - 8; x < W / 2 + 8; x++)
        {
            double xm = (x + 0.5 - W / 2) * P, sum = 0;
            int m = 20000;
            for (int i = 0; i <= m; i++)
            {
                double nu = nuC * i / m, r = nu / nuC;
                double otf = 2 / Math.PI * (Math.Acos(r) - r * Math.Sqrt(1 - r * r));
                double sinc = nu == 0 ? 1 : Math.Sin(Math.PI * nu * P) / (Math.PI * nu * P);
                double f = nu == 0 ? 2 * Math.PI * xm : Math.Sin(2 * Math.PI * nu * xm) / nu;
                sum += (i == 0 || i == m ? 1 : i % 2 == 1 ? 4 : 2) * otf * sinc * f;
            }
            double expected = 0.5 + sum * nuC / m / 3 / Math.PI;
            worst = Math.Max(worst, Math.Abs(data[W + x] - expected));
        }
        Console.WriteLine($"edge at energy {energy}: worst {worst}");
        Assert.True(worst <= tolerance, $"edge response off by {worst} (kernel radius {kernel.Radius}, energy {kernel.CapturedEnergy})");
    }

    /// <summary>cos⁴ of each pixel's field angle: the angle between the render camera's ray through the pixel centre and its
    /// axis.</summary>
    [Fact]
    public void Cos4th_IsTheFourthPowerOfTheCosineOfTheRenderCamerasRayAngle()
    {
        const int W = 20, H = 12;
        var camera = new Camera(new Vector3(0, 0, 10), Vector3.Zero, Vector3.UnitY, 50, W, H, 1);
        var r = Optics.RelativeIllumination(W, H, 50);
        var axis = Vector3.Normalize(-camera.Position);
        foreach (var (x, y) in new[] { (0, 0), (19, 11), (10, 6), (3, 9), (19, 0) })
        {
            var d = camera.Generate(x + 0.5f, y + 0.5f).Direction;
            double cos = Vector3.Dot(Vector3.Normalize(d), axis);
            Assert.Equal(Math.Pow(cos, 4), r[y * W + x], 5);
        }
        // The focal length that gives 12 rows of 2.8 µm a 50° vertical field: 12·2.8 µm / (2 tan 25°).
        Assert.Equal(12 * 2.8e-3 / (2 * Math.Tan(25 * Math.PI / 180)), Optics.FocalLengthMm(H, 2.8, 50), 12);
    }

    const string Flat = """
        {
          "name": "flat", "bands": "380:780:10", "white": "D65", "integration": "exact",
          "camera": { "position": [0, 0, 10], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 60, "width": 24, "height": 16, "spp": 1 },
          "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "D65", "intensity": 1 } ],
          "objects": [ { "type": "quad", "name": "wall", "center": [0, 0, 0], "normal": [0, 0, 1], "size": [100, 100],
                         "material": { "diffuse": "colorchecker:19" } } ],
          "background": 0
        }
        """;

    /// <summary>The wall rendered once for the class (24 × 16, 40 bands).</summary>
    static readonly Lazy<string> Wall = new(RenderWall);

    static string FlatRender() => Wall.Value;

    static string RenderWall()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "flat.json"), Flat);
        var (code, _, err) =
            CliRunner.Run("render", Path.Combine(dir, "flat.json"), "-o", Path.Combine(dir, "out"), "--formats", "npy,aov", "--quiet");
        Assert.True(code == 0, err);
        return Path.Combine(dir, "out");
    }

    static float[] Raw(string render, string name, params string[] extra)
    {
        var cam = Path.Combine(render, name);
        var (code, _, err) = CliRunner.Run(["camera", render, "--noise", "off", "--exposure", "1e-6", "-o", cam, .. extra]);
        Assert.True(code == 0, err);
        return SpectralRenderer.Imaging.NpyReader.Read(File.OpenRead(Path.Combine(cam, "raw.npy"))).Data;
    }

    /// <summary>
    /// A uniform wall head-on under a directional light (the same radiance at every pixel): the raw of each pixel with
    /// cos⁴ on over the raw with a flat lens is cos⁴ of its field angle, and the Airy blur leaves a uniform field as it is.
    /// </summary>
    [Fact]
    public void UniformWall_RawFallsOffAsCos4th_AndTheBlurKeepsAUniformField()
    {
        var render = FlatRender();
        var flat = Raw(render, "flat", "--sensor", "wheel-6", "--off-axis", "none", "--psf", "none");
        var fall = Raw(render, "cos4", "--sensor", "wheel-6", "--psf", "none");
        var blurred = Raw(render, "blur", "--sensor", "wheel-6", "--off-axis", "none");
        double t = Math.Tan(30 * Math.PI / 180), aspect = 24.0 / 16;
        for (int y = 0; y < 16; y++)
            for (int x = 0; x < 24; x++)
            {
                int i = (y * 24 + x) * 6 + (x + y) % 6;
                double sx = (2 * (x + 0.5) / 24 - 1) * t * aspect, sy = (1 - 2 * (y + 0.5) / 16) * t;
                double cos2 = 1 / (1 + sx * sx + sy * sy);
                Assert.Equal(cos2 * cos2, fall[i] / flat[i], 5);
                Assert.Equal(1, blurred[i] / flat[i], 5);
            }
    }

    /// <summary>
    /// "transmittance" as a spectrum: every channel's signal is ∫ ρ·E·η·T·λ/(hc) dλ — against a 0.1 nm midpoint sum of the
    /// tables' linear interpolants here (wheel-6 on a flat wall, flat lens): on the exact route within 1e-4; on the band
    /// route (which takes the light's shape within each band, off by up to 7 % here at F420 with or without a lens) the
    /// signal with the lens over the signal without it equals the integrals' ratio within 5e-3.
    /// </summary>
    [Theory]
    [InlineData("exact")]
    [InlineData("bands")]
    public void TransmittanceSpectrum_MultipliesTheSignal_WavelengthByWavelength(string route)
    {
        var render = FlatRender();
        var dir = Path.GetDirectoryName(render)!;
        File.WriteAllText(Path.Combine(dir, "lens.csv"), "wavelength,T\n380,0.4\n450,0.9\n520,0.95\n600,0.7\n780,0.5\n");
        File.WriteAllText(Path.Combine(dir, "lens.json"),
            """{ "preset": "wheel-6", "transmittance": "lens.csv:T", "off_axis": "none", "psf": "none" }""");
        // the folder is shared: same files
        var raw = Raw(render, "lens-" + route, "--sensor", Path.Combine(dir, "lens.json"), "--signals", route);
        var bare = Raw(render, "bare-" + route, "--sensor", "wheel-6", "--off-axis", "none", "--psf", "none", "--signals", route);
        var sensor = SensorPresets.Get("wheel-6");
        var d65 = ExactSignalsTests.Table("illuminants.csv", "D65");
        var header = File.ReadLines(Path.Combine(SpectralRenderer.Spectra.DataDirectory.Path, "colorchecker-ohta.csv")).First().Split(',');
        var rho = ExactSignalsTests.Table("colorchecker-ohta.csv", header[19]);
        var lens = (new double[] { 380, 450, 520, 600, 780 }, new double[] { 0.4, 0.9, 0.95, 0.7, 0.5 });
        const double h = 6.62607015e-34, c0 = 299792458;
        int pixel = 8 * 24 + 12;
        for (int c = 0; c < sensor.ChannelCount; c++)
        {
            var ch = sensor.Channels[c];
            var qe = (ch.QuantumEfficiency.Wavelengths.ToArray(), ch.QuantumEfficiency.Values.ToArray());
            double withLens = 0, without = 0;
            for (int k = 0; k < 4000; k++)
            {
                double wl = 380 + (k + 0.5) * 0.1;
                double f = ExactSignalsTests.Lerp(rho, wl) * ExactSignalsTests.Lerp(d65, wl) * ExactSignalsTests.Lerp(qe,
                    wl) * wl * 1e-9 / (
                    h * c0) * 0.1;
                withLens += f * ExactSignalsTests.Lerp(lens, wl);
                without += f;
            }
            double expected = sensor.SystemGain * 1e-6 * sensor.Etendue * withLens;
            if (route == "exact")
                Assert.True(Math.Abs(raw[pixel * 6 + c] / expected - 1) < 1e-4, $"{ch.Name}: {raw[pixel * 6 + c]} vs {expected}");
            else
                Assert.True(Math.Abs(raw[pixel * 6 + c] / bare[pixel * 6 + c] / (withLens / without) - 1) < 5e-3,
                    $"{ch.Name}: ratio {raw[pixel * 6 + c] / bare[pixel * 6 + c]} vs {withLens / without}");
        }
    }

    [Fact]
    public void BadOpticsSettings_AreOneLineErrors()
    {
        var render = FlatRender();
        var (code, _, err) = CliRunner.Run("camera", render, "--sensor", "isetcam", "--off-axis", "cos3");
        Assert.Equal(2, code);
        Assert.Contains("--off-axis", err);
        Assert.Contains("cos4th", err);
        var file = Path.Combine(Path.GetDirectoryName(render)!, "bad.json");
        File.WriteAllText(file, """{ "psf": "gauss" }""");
        (code, _, err) = CliRunner.Run("camera", render, "--sensor", file);
        Assert.Equal(2, code);
        Assert.Contains("$.psf", err);
        Assert.Single(err.Trim().Split('\n'));
    }
}
