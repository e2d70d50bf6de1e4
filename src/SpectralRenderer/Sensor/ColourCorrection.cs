using SpectralRenderer.Color;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Sensor;

/// <summary>
/// Camera signals to colour, as ISETCam's image processor and pbrt-v4's PixelSensor do it:
/// <list type="number">
/// <item>white balance: each channel divided by its response to the perfect white diffuser under the scene light,
/// s_c = ė_c / ė_c,white with ė_c,white = Σ_b w_c,b E_b (E_b the light's band values: the white's radiance in the render);</item>
/// <item>a 3 × C colour-correction matrix M, XYZ = M·s, fitted by least squares to the 24 ColorChecker (Ohta) patches
/// under the scene light: their balanced signals simulated from their band reflectances, their exact XYZ integrated
/// on the CIE tables at 1 nm (white Y = 1);</item>
/// <item>XYZ to sRGB (IEC 61966-2-1).</item>
/// </list>
/// On the exact route (<see cref="RadianceCube.ChannelIntegrals"/>) the white's and the patches' signals are the exact
/// integrals ∫ η_c·λ·E·ρ dλ instead of band sums, as the captured signals are. The white is the render's: its radiance
/// is WhiteScale × E (E·intensity/π under physical radiometry, see docs/camera.md), so the balanced
/// signals of a patch do not depend on the radiometry or the light's intensity.
/// </summary>
public sealed class ColourCorrection
{
    ColourCorrection(double[] whiteRate, double[,] matrix, Xyz[] targets, double[][] signals, Xyz white, double whiteScale,
        bool exactSignals)
    {
        WhiteRate = whiteRate; Matrix = matrix; Targets = targets; TrainingSignals = signals; White = white; WhiteScale = whiteScale;
        ExactSignals = exactSignals;
    }

    /// <summary>Whether the white and the patches' signals are the exact route's full-resolution integrals (else band sums).</summary>
    public bool ExactSignals { get; }

    /// <summary>The render's white diffuser radiance per unit of the light's band values (1: the paper's white, E).</summary>
    public double WhiteScale { get; }

    /// <summary>ė_c of the white diffuser (e⁻/s).</summary>
    public double[] WhiteRate { get; }
    /// <summary>3 × C: XYZ from white-balanced signals.</summary>
    public double[,] Matrix { get; }
    /// <summary>The exact XYZ of the 24 patches under the scene light (1 nm, white Y = 1).</summary>
    public Xyz[] Targets { get; }
    public double[][] TrainingSignals { get; }
    /// <summary>The 1 nm XYZ of the white diffuser under the scene light.</summary>
    public Xyz White { get; }

    /// <param name="exact">The sensor, for the exact route's full-resolution signals; null for band sums.</param>
    public static ColourCorrection Fit(ChannelWeights weights, BandGrid grid, TabulatedSpectrum light, Observer observer,
        SensorModel? exact = null, double whiteScale = 1)
    {
        int cc = weights.Channels, n = grid.Count;
        var e = BandProjection.Means(light, grid);
        var whiteRate = new double[cc];
        for (int c = 0; c < cc; c++)
            if (exact is null) for (int b = 0; b < n; b++) whiteRate[c] += weights[c, b] * e[b];
            else whiteRate[c] = weights.Factor * ChannelWeights.ExactIntegral(exact.Channels[c], light, null, grid.Start, grid.End);
        var reference = new ReferenceColorimeter(observer, light, grid.Start, grid.End);
        var targets = new Xyz[ColorChecker.PatchCount];
        var signals = new double[ColorChecker.PatchCount][];
        var s = new double[cc, ColorChecker.PatchCount];
        var t = new double[3, ColorChecker.PatchCount];
        for (int p = 0; p < ColorChecker.PatchCount; p++)
        {
            // Ohta's tables span 380–780 nm; a render's bands may reach into the UV or the near infrared, where the patch's
            // first and last values continue (CIE 015's extrapolation for short tables).
            var patch = ColorChecker.Patch(p + 1).WithExtrapolation(Extrapolation.Clamp);
            var r = BandProjection.Means(patch, grid);
            signals[p] = new double[cc];
            for (int c = 0; c < cc; c++)
            {
                double v = 0;
                if (exact is null) for (int b = 0; b < n; b++) v += weights[c, b] * e[b] * r[b];
                else v = weights.Factor * ChannelWeights.ExactIntegral(exact.Channels[c], light, patch, grid.Start, grid.End);
                signals[p][c] = s[c, p] = whiteRate[c] > 0 ? v / whiteRate[c] : 0;
            }
            targets[p] = reference.OfReflectance(patch);
            t[0, p] = targets[p].X; t[1, p] = targets[p].Y; t[2, p] = targets[p].Z;
        }
        double[,] m;
        if (cc == 1)
        {   // Monochrome: a grey image. XYZ = s·y·(X_w, Y_w, Z_w)/Y_w — the white's chromaticity (a* = b* = 0) — with y fitted on Y.
            double sy = 0, ss = 0;
            for (int p = 0; p < ColorChecker.PatchCount; p++) { sy += s[0, p] * t[1, p]; ss += s[0, p] * s[0, p]; }
            double y = ss > 0 ? sy / ss : 0, wy = reference.White.Y;
            m = new double[3, 1] { { y * reference.White.X / wy }, { y }, { y * reference.White.Z / wy } };
        }
        else
        {
            // M = T·Sᵀ (S·Sᵀ + εI)⁻¹; ε (1e-9 of the mean diagonal) only keeps a many-channel fit on 24 patches solvable.
            var sst = Dense.Multiply(s, Dense.Transpose(s));
            double eps = 1e-9 * Dense.Trace(sst) / cc;
            m = Dense.SolveRight(Dense.Multiply(t, Dense.Transpose(s)), Dense.Add(sst, Dense.Identity(cc, eps)));
        }
        for (int c = 0; c < cc; c++) whiteRate[c] *= whiteScale;
        return new ColourCorrection(whiteRate, m, targets, signals, reference.White, whiteScale, exact is not null);
    }

    /// <summary>XYZ of white-balanced signals.</summary>
    public Xyz ToXyz(ReadOnlySpan<double> balanced)
    {
        double x = 0, y = 0, z = 0;
        for (int c = 0; c < balanced.Length; c++)
        {
            x += Matrix[0, c] * balanced[c];
            y += Matrix[1, c] * balanced[c];
            z += Matrix[2, c] * balanced[c];
        }
        return new Xyz(x, y, z);
    }
}
