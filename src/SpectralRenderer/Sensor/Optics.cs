using System.Collections.Concurrent;
using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Sensor;

/// <summary>Off-axis irradiance fall-off of the lens (sensor file key <c>"off_axis"</c>).</summary>
public enum OffAxisModel
{
    /// <summary>cos⁴ of the field angle (ISETCam's default <c>opticsCos4th</c>).</summary>
    Cos4th,
    /// <summary>No fall-off: every pixel gets the on-axis irradiance.</summary>
    None,
}

/// <summary>Point spread of the lens (sensor file key <c>"psf"</c>).</summary>
public enum PsfModel
{
    /// <summary>The diffraction-limited Airy pattern of a circular pupil at the f-number, per band (ISETCam's default diffraction-limited
    /// optics).</summary>
    Diffraction,
    /// <summary>No blur: a pixel receives only its own radiance.</summary>
    None,
}

/// <summary>
/// The lens between the scene and the pixels, as ISETCam's default shift-invariant optics model it (oiCompute with
/// diffraction-limited optics): the irradiance E = L·πT/(1 + 4N²) of <see cref="SensorModel.Etendue"/> on the axis,
/// <list type="bullet">
/// <item>times the relative illumination cos⁴φ at field angle φ (ISETCam <c>cos4th.m</c>, its form for a distant image,
/// (d/√(d² + r²))⁴ with d the image distance and r the image height: tan φ = r/d). A thin lens focused at infinity has
/// d = f and its chief ray undeviated, so φ is the render's own camera-ray angle: with the render's pinhole camera
/// (its Generate), tan²φ = s_x² + s_y² at the pixel centre, s = the film coordinates × tan(fov/2);</item>
/// <item>convolved with the diffraction-limited point spread function of a circular pupil at the band's centre
/// wavelength (Goodman, Introduction to Fourier Optics, 3rd ed., §4.4.2, eq. 4-31): the Airy pattern
/// PSF(r) = π/(4(λN)²)·[2 J₁(v)/v]², v = π r/(λN), unit energy, first zero at v = 3.8317, r = 1.2197 λN.</item>
/// </list>
/// The focal length follows from the render's field of view and the sensor: f = H·p/(2 tan(fov/2)) (H rows of pitch p);
/// the Airy pattern on the sensor depends on λ and N only. The render's pixel value is the mean radiance over the pixel's
/// square and a photosite integrates its square, so the pixel-to-pixel kernel is the Airy pattern weighed by the triangle
/// Λ(x/p − i)·Λ(y/p − j) (a box correlated with a box), integrated by 3-point Gauss–Legendre on quarter pixels; it is cut
/// where the encircled energy 1 − J₀²(v) − J₁²(v) passes <see cref="PsfEnergy"/> (the Airy tail holds 2/(πv) of the energy
/// beyond v) and normalised to 1, so a uniform field keeps its value and the far tail's share goes to the kernel. At the
/// image's edge the radiance is taken to continue as the edge pixel's (clamped). Applied to the irradiance before the
/// pixels sample it: cos⁴ first, then the blur, as ISETCam's opticsDLCompute does.
/// </summary>
public static class Optics
{
    /// <summary>The share of the Airy pattern's energy the kernel's disc holds before normalisation (the rest is the far tail).</summary>
    public const double PsfEnergy = 0.97;

    /// <summary>
    /// What the sensor's optics do to a W × H capture on a band grid: the relative illumination per pixel (null: none —
    /// <see cref="OffAxisModel.None"/>, or no field of view known for a cube that is not a render) and one kernel per band
    /// at its centre wavelength (null: <see cref="PsfModel.None"/>).
    /// </summary>
    public sealed record Plan(OffAxisModel OffAxis, PsfModel Psf, double? FovDegrees, double? FocalLengthMm, double[]? Illumination,
        Kernel[]? Kernels)
    {
        public bool Any => Illumination is not null || Kernels is not null;
        /// <summary>The darkest pixel's relative illumination (1 without fall-off).</summary>
        public double MinIllumination => Illumination is { Length: > 0 } r ? r.Min() : 1;
    }

    /// <summary>The plan for <paramref name="sensor"/> on a render of <paramref name="width"/> × <paramref name="height"/> pixels with
    /// vertical field of view <paramref name="fovDegrees"/>.</summary>
    public static Plan For(SensorModel sensor, int width, int height, double? fovDegrees, Spectra.BandGrid grid)
    {
        var illumination = sensor.OffAxis == OffAxisModel.Cos4th && fovDegrees is { } f ? RelativeIllumination(width, height, f) : null;
        var kernels = sensor.Psf == PsfModel.Diffraction
            ? Enumerable.Range(0, grid.Count).Select(b => AiryKernel(grid.Centre(b), sensor.FNumber, sensor.PixelSizeMicrons)).ToArray()
            : null;
        return new Plan(sensor.OffAxis, sensor.Psf, fovDegrees,
            fovDegrees is { } fv ? FocalLengthMm(height, sensor.PixelSizeMicrons, fv) : null,
            illumination, kernels);
    }

    /// <summary>The relative illumination cos⁴φ at film coordinates (s_x, s_y) = tan φ's components.</summary>
    public static double Cos4th(double sx, double sy)
    {
        double c2 = 1 / (1 + sx * sx + sy * sy);
        return c2 * c2;
    }

    /// <summary>
    /// Per pixel (row-major, row 0 at the top), cos⁴ of the field angle of the pixel centre for a film of
    /// <paramref name="width"/> × <paramref name="height"/> pixels and vertical field of view <paramref name="fovDegrees"/>
    /// (the render camera's <c>Generate</c>: s_x = (2(x + ½)/W − 1)·tan(fov/2)·W/H, s_y = (1 − 2(y + ½)/H)·tan(fov/2)).
    /// </summary>
    public static double[] RelativeIllumination(int width, int height, double fovDegrees)
    {
        double t = Math.Tan(fovDegrees * Math.PI / 360), aspect = (double)width / height;
        var r = new double[width * height];
        for (int y = 0; y < height; y++)
        {
            double sy = (1 - 2 * (y + 0.5) / height) * t;
            for (int x = 0; x < width; x++) r[y * width + x] = Cos4th((2 * (x + 0.5) / width - 1) * t * aspect, sy);
        }
        return r;
    }

    /// <summary>The focal length (mm) that gives a sensor of <paramref name="rows"/> rows of pitch p the render's vertical field of
    /// view.</summary>
    public static double FocalLengthMm(int rows, double pixelMicrons, double fovDegrees) =>
        rows * pixelMicrons * 1e-3 / (2 * Math.Tan(fovDegrees * Math.PI / 360));

    /// <summary>The Airy pattern's irradiance at radius r (µm) per unit power, µm⁻²: π/(4(λN)²)·[2J₁(v)/v]², v = πr/(λN).</summary>
    public static double Airy(double radiusMicrons, double wavelengthNm, double fNumber)
    {
        double ln = wavelengthNm * 1e-3 * fNumber, v = Math.PI * radiusMicrons / ln;
        double a = v < 1e-8 ? 1 : 2 * BesselJ(1, v) / v;
        return Math.PI / (4 * ln * ln) * a * a;
    }

    /// <summary>The share of the Airy pattern's energy within radius r: 1 − J₀²(v) − J₁²(v) (Rayleigh; Born &amp; Wolf §8.5.2).</summary>
    public static double EncircledEnergy(double radiusMicrons, double wavelengthNm, double fNumber)
    {
        double v = Math.PI * radiusMicrons / (wavelengthNm * 1e-3 * fNumber), j0 = BesselJ(0, v), j1 = BesselJ(1, v);
        return 1 - j0 * j0 - j1 * j1;
    }

    /// <summary>
    /// J₀ and J₁: the power series Σ (−1)^k (x/2)^{2k+n}/(k!(k+n)!) below x = 12 (cancellation costs at most ~1e-12
    /// there), Hankel's asymptotic expansion above (DLMF 10.17.3, summed to its smallest term, which is below 1e-11 at x ≥ 12).
    /// </summary>
    public static double BesselJ(int n, double x)
    {
        if (n is not (0 or 1)) throw new ArgumentOutOfRangeException(nameof(n));
        double sign = n == 1 && x < 0 ? -1 : 1;
        x = Math.Abs(x);
        if (x < 12)
        {
            double q = -x * x / 4, term = n == 0 ? 1 : x / 2, sum = term;
            for (int k = 1; k < 80 && Math.Abs(term) > 1e-17 * Math.Abs(sum); k++) { term *= q / (k * (k + n)); sum += term; }
            return sign * sum;
        }
        double mu = 4.0 * n * n, z = 8 * x, p = 0, qq = 0, t = 1, last = double.MaxValue;
        for (int k = 0; k < 60; k++)
        {
            if (k > 0)
            {
                double next = t * (mu - (2 * k - 1) * (2 * k - 1)) / (k * z);
                if (Math.Abs(next) >= last) break;   // the asymptotic series starts to grow: stop at its smallest term
                t = next;
            }
            last = Math.Abs(t);
            // P = Σ_k even (−1)^{k/2} a_k, Q = Σ_k odd (−1)^{(k−1)/2} a_k, a_k = Π_{j ≤ k} (μ − (2j−1)²)/(j·8x)
            if (k % 2 == 0) p += (k / 2 % 2 == 0 ? 1 : -1) * t;
            else qq += ((k - 1) / 2 % 2 == 0 ? 1 : -1) * t;
        }
        double chi = x - (n / 2.0 + 0.25) * Math.PI;
        return sign * Math.Sqrt(2 / (Math.PI * x)) * (p * Math.Cos(chi) - qq * Math.Sin(chi));
    }

    /// <summary>A pixel-to-pixel kernel: (2R + 1)² weights, row-major, summing to 1, and the Airy energy its disc held before
    /// normalisation.</summary>
    public sealed record Kernel(int Radius, double[] Weights, double CapturedEnergy, double WavelengthNm)
    {
        public int Side => 2 * Radius + 1;
        public double this[int dx, int dy] => Weights[(dy + Radius) * Side + dx + Radius];
    }

    static readonly ConcurrentDictionary<(double, double, double, double), Kernel> Kernels = new();

    /// <summary>The Airy kernel at <paramref name="wavelengthNm"/> for pixels of pitch p µm (cached), cut at the radius holding
    /// <paramref name="energy"/>.</summary>
    public static Kernel AiryKernel(double wavelengthNm, double fNumber, double pixelMicrons, double energy = PsfEnergy) =>
        Kernels.GetOrAdd((wavelengthNm, fNumber, pixelMicrons, energy), k => BuildKernel(k.Item1, k.Item2, k.Item3, k.Item4));

    static Kernel BuildKernel(double lambda, double fNumber, double p, double energy)
    {
        // The radius (pixels) where the encircled energy reaches the target: bisection on EE (monotone up to its ripples).
        double ln = lambda * 1e-3 * fNumber, rMax = ln;
        while (EncircledEnergy(rMax, lambda, fNumber) < energy && rMax < 1e4 * ln) rMax *= 1.5;
        int radius = Math.Max(1, (int)Math.Ceiling(rMax / p));
        int side = 2 * radius + 1;
        // Quadrature nodes per axis on [−(R+1)p, (R+1)p]: 4 sub-cells per pixel, 3 Gauss–Legendre nodes each; the triangle
        // weights are linear on each pixel, so only the Airy pattern limits the accuracy.
        const int Sub = 4;
        double g = Math.Sqrt(0.6);
        double[] gx = [-g, 0, g], gw = [5.0 / 9, 8.0 / 9, 5.0 / 9];
        int cells = 2 * (radius + 1) * Sub, nodes = cells * 3;
        var pos = new double[nodes];
        var wq = new double[nodes];
        double h = p / Sub;
        for (int c = 0; c < cells; c++)
            for (int q = 0; q < 3; q++)
            {
                pos[c * 3 + q] = -(radius + 1) * p + (c + 0.5) * h + 0.5 * h * gx[q];
                wq[c * 3 + q] = 0.5 * h * gw[q];
            }
        // Triangle weight of node i for kernel offset d: Λ(u/p − d).
        var tri = new double[side * nodes];
        for (int d = -radius; d <= radius; d++)
            for (int i = 0; i < nodes; i++) tri[(d + radius) * nodes + i] = Math.Max(0, 1 - Math.Abs(pos[i] / p - d)) * wq[i];
        // The Airy pattern on the node grid (symmetric: one quadrant evaluated).
        var airy = new double[nodes * nodes];
        int half = nodes / 2;
        for (int j = half; j < nodes; j++)
            for (int i = j; i < nodes; i++)
            {
                double a = Airy(Math.Sqrt(pos[i] * pos[i] + pos[j] * pos[j]), lambda, fNumber);
                int i2 = nodes - 1 - i, j2 = nodes - 1 - j;
                airy[j * nodes + i] = airy[j2 * nodes + i] = airy[j * nodes + i2] = airy[j2 * nodes + i2] = a;
                airy[i * nodes + j] = airy[i2 * nodes + j] = airy[i * nodes + j2] = airy[i2 * nodes + j2] = a;
            }
        // K[dy, dx] = Σ_j Σ_i Λ_dy(j) Λ_dx(i) Airy(i, j): rows first, then columns.
        var rows = new double[side * nodes];
        for (int dx = 0; dx < side; dx++)
            for (int j = 0; j < nodes; j++)
            {
                double s = 0;
                for (int i = 0; i < nodes; i++) s += tri[dx * nodes + i] * airy[j * nodes + i];
                rows[dx * nodes + j] = s;
            }
        var k = new double[side * side];
        double total = 0;
        for (int dy = 0; dy < side; dy++)
            for (int dx = 0; dx < side; dx++)
            {
                double s = 0;
                for (int j = 0; j < nodes; j++) s += tri[dy * nodes + j] * rows[dx * nodes + j];
                k[dy * side + dx] = s;
                total += s;
            }
        for (int i = 0; i < k.Length; i++) k[i] /= total;
        return new Kernel(radius, k, total, lambda);
    }

    /// <summary>
    /// The optics applied to pixel-interleaved planes (H × W × planes, row 0 at the top) in place: each value times the
    /// pixel's relative illumination (null: none), then each plane convolved with its kernel (null: no blur; plane k uses
    /// <paramref name="kernels"/>[k], or [0] for all). With <paramref name="planeOf"/> (a mosaic: the one plane each pixel
    /// reads) only that plane of each pixel is blurred, the others are left as they were. The same operations in the same
    /// order for any thread count.
    /// </summary>
    public static void Apply(float[] data, int width, int height, int planes, double[]? illumination, Kernel[]? kernels, int threads = -1,
        int[]? planeOf = null)
    {
        var parallel = new ParallelOptions { MaxDegreeOfParallelism = threads };
        if (illumination is not null)
            Parallel.For(0, height, parallel, y =>
            {
                for (int x = 0; x < width; x++)
                {
                    float r = (float)illumination[y * width + x];
                    var s = data.AsSpan((y * width + x) * planes, planes);
                    for (int k = 0; k < planes; k++) s[k] *= r;
                }
            });
        if (kernels is null || kernels.Length == 0) return;
        int radius = kernels.Max(k => k.Radius), side = 2 * radius + 1, vc = Vector<float>.Count;
        int stride = (planes + vc - 1) / vc * vc;
        // Per tap, the planes' weights side by side (zeros past a smaller kernel's edge and past the last plane); the taps
        // that are zero for every plane are left out.
        var weights = new float[side * side * stride];
        for (int k = 0; k < planes; k++)
        {
            var kern = kernels[kernels.Length == 1 ? 0 : k];
            for (int dy = -kern.Radius; dy <= kern.Radius; dy++)
                for (int dx = -kern.Radius; dx <= kern.Radius; dx++)
                    weights[((dy + radius) * side + dx + radius) * stride + k] = (float)kern[dx, dy];
        }
        var tapList = new List<(int Dx, int Dy, int Offset)>();
        for (int t = 0; t < side * side; t++)
            if (weights.AsSpan(t * stride, stride).ContainsAnyExcept(0f)) tapList.Add((t % side - radius, t / side - radius, t * stride));
        var taps = tapList.ToArray();
        // The source padded to whole vectors per pixel.
        var src = new float[(long)width * height * stride];
        for (int i = 0; i < width * height; i++) data.AsSpan(i * planes, planes).CopyTo(src.AsSpan(i * stride, planes));
        Parallel.For(0, height, parallel, () => new float[stride], (y, _, acc) =>
        {
            for (int x = 0; x < width; x++)
            {
                int o = (y * width + x) * planes;
                if (planeOf is not null)
                {
                    int k = planeOf[y * width + x];
                    float v = 0;
                    foreach (var (dx, dy, off) in taps)
                        v += weights[off + k] * src[(Math.Clamp(y - dy, 0, height - 1) * width + Math.Clamp(x - dx, 0, width - 1)) * stride
                            + k];
                    data[o + k] = v;
                    continue;
                }
                Array.Clear(acc);
                foreach (var (dx, dy, off) in taps)
                {
                    int so = (Math.Clamp(y - dy, 0, height - 1) * width + Math.Clamp(x - dx, 0, width - 1)) * stride;
                    for (int i = 0; i < stride; i += vc)
                        (new Vector<float>(acc, i) + new Vector<float>(weights, off + i) * new Vector<float>(src, so + i)).CopyTo(acc, i);
                }
                acc.AsSpan(0, planes).CopyTo(data.AsSpan(o, planes));
            }
            return acc;
        }, _ => { });
    }
}
