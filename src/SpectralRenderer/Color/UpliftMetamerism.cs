using SpectralRenderer.Spectra;

namespace SpectralRenderer.Color;

/// <summary>
/// What the choice of metamer costs an RGB texture: for an sRGB colour, two reflectances with the same colour under D65
/// (CIE 1931 2°) — the smooth sigmoid-polynomial one the renderer uses (<see cref="SigmoidUplift"/>) and a three-box one
/// (constant over 380–490, 490–590 and 590–780 nm, the weights solved for the colour, admissible when all lie in [0, 1])
/// — and their CIEDE2000 difference under other lights, each colour taken relative to that light's own white (a perfect
/// reflector under it has Y = 1 and is the Lab white, no chromatic adaptation transform).
/// </summary>
public sealed class UpliftMetamerism
{
    /// <summary>The lights of the report: incandescent A, fluorescent FL2 and FL11, two white LEDs.</summary>
    public static string[] DefaultLights { get; } = ["A", "FL2", "FL11", "led-rgb", "led-yag"];

    /// <summary>The box edges of the second metamer, nm.</summary>
    public static double[] BoxEdges { get; } = [380, 490, 590, 780.0001];

    readonly SigmoidUplift _uplift;
    readonly double[][] _boxes;
    readonly double[,] _boxXyzInverse;   // XYZ under D65 → box weights

    public UpliftMetamerism(SigmoidUplift uplift)
    {
        _uplift = uplift;
        var wl = SigmoidUplift.Wavelengths;
        _boxes = new double[3][];
        var m = new double[3, 3];
        for (int k = 0; k < 3; k++)
        {
            _boxes[k] = wl.Select(l => l >= BoxEdges[k] && l < BoxEdges[k + 1] ? 1.0 : 0.0).ToArray();
            var xyz = uplift.Colour(_boxes[k]);
            m[0, k] = xyz.X; m[1, k] = xyz.Y; m[2, k] = xyz.Z;
        }
        _boxXyzInverse = Matrix3.Inverse(m);
    }

    /// <summary>The three-box reflectance with the colour <paramref name="target"/> under D65, and whether it lies in [0, 1].</summary>
    public double[] BoxMetamer(Xyz target, out bool admissible)
    {
        var w = Matrix3.Apply(_boxXyzInverse, target);
        double[] weights = [w.X, w.Y, w.Z];
        admissible = weights.All(v => v >= -1e-9 && v <= 1 + 1e-9);
        var r = new double[SigmoidUplift.Wavelengths.Length];
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < r.Length; j++) r[j] += weights[k] * _boxes[k][j];
        return r;
    }

    /// <summary>ΔE00 between the sigmoid and the box metamer of an sRGB colour (codes out of <paramref name="max"/>) under each light; null
    /// when the box metamer is not a reflectance.</summary>
    public double[]? Spread(int r, int g, int b, int max, IReadOnlyList<Colorimeter> lights)
    {
        var smooth = _uplift.FromSrgbCodes(r, g, b, max);
        var box = BoxMetamer(SigmoidUplift.FromSrgb((double)r / max, (double)g / max, (double)b / max), out bool admissible);
        if (!admissible) return null;
        var result = new double[lights.Count];
        for (int i = 0; i < lights.Count; i++) result[i] = Difference(lights[i], smooth, box);
        return result;
    }

    /// <summary>ΔE00 between two reflectances tabulated at <see cref="SigmoidUplift.Wavelengths"/> under <paramref name="light"/>'s
    /// colorimeter.</summary>
    public static double Difference(Colorimeter light, double[] a, double[] b)
    {
        var white = light.OfReflectance(Table(Enumerable.Repeat(1.0, a.Length).ToArray()));
        return DeltaE2000.Between(Lab.FromXyz(light.OfReflectance(Table(a)), white), Lab.FromXyz(light.OfReflectance(Table(b)), white));
    }

    /// <summary>A colorimeter for light <paramref name="name"/> (CIE 1931 2°, exact integration, white Y = 1).</summary>
    public static Colorimeter Under(string name) =>
        new(BandGrid.Default, Observer.Cie1931, SpectrumLibrary.Resolve(name), BandIntegration.Exact, false, 1);

    static TabulatedSpectrum Table(double[] r) => new("metamer", SigmoidUplift.Wavelengths, r, Extrapolation.Clamp);
}
