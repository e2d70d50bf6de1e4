using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;

namespace SpectralRenderer.Scenes;

/// <summary>The lobes a BSDF has, and the kind of lobe a sampled direction came from.</summary>
[Flags]
public enum BsdfFlags
{
    None = 0,
    Reflection = 1,
    Transmission = 2,
    /// <summary>A smooth lobe spread over the hemisphere (Lambert).</summary>
    Diffuse = 4,
    /// <summary>A smooth lobe around the mirror direction (Phong, Blinn–Phong).</summary>
    Glossy = 8,
    /// <summary>A lobe concentrated in one direction (perfect mirror, specular transmission): no pdf, no Evaluate.</summary>
    Delta = 16,
}

/// <summary>A direction drawn from the smooth lobes of a BSDF: ωi, its solid-angle pdf and the lobe it came from.</summary>
public readonly record struct BsdfSample(Vector3 Wi, float Pdf, BsdfFlags Flags);

/// <summary>
/// A surface's scattering in physical radiometry: f(ωo, ωi) per band in 1/sr, so reflected radiance is
/// L_o = ∫ f · L_i · cos θ_i dωi. ωo points towards the viewer, ωi towards the light, n is the unit shading normal
/// (either side: the surfaces of eq. 2 are two-sided, the side ωo is on counts as the front). Band spectra are spans
/// of band values; the BSDF fills as many as the span holds (at most the scene's padded band count).
/// The smooth lobes answer <see cref="Evaluate(Vector3, Vector3, Vector3, Span{float})"/>, <see cref="Sample"/> and <see cref="Pdf"/>; the
/// delta lobes (perfect mirror k_r, specular transmission k_t) answer <see cref="SampleMirror"/> and <see cref="SampleTransmission"/>.
/// </summary>
public abstract class Bsdf
{
    /// <summary>The lobes this BSDF has.</summary>
    public abstract BsdfFlags Lobes { get; }

    /// <summary>f(ωo, ωi) of the smooth lobes, per band, in 1/sr (delta lobes excluded).</summary>
    public abstract void Evaluate(Vector3 wo, Vector3 wi, Vector3 n, Span<float> f);

    /// <summary>
    /// Does the model take a texture's texel in place of its diffuse reflectance or specular weight
    /// (<see cref="Evaluate(Vector3, Vector3, Vector3, ReadOnlySpan{float}, ReadOnlySpan{float}, Span{float})"/>)?
    /// </summary>
    public virtual bool TakesTextures => false;

    /// <summary>
    /// f(ωo, ωi) of the smooth lobes with the diffuse reflectance <paramref name="diffuse"/> and the specular weight
    /// <paramref name="specular"/> of this point (a texture's filtered texel, on the BSDF's grid) in place of the BSDF's own;
    /// an empty span keeps its own. Sampling and <see cref="Pdf"/> stay the BSDF's (an estimator's weight f·cos/pdf stays
    /// unbiased for any density that covers f).
    /// </summary>
    public virtual void Evaluate(Vector3 wo, Vector3 wi, Vector3 n, ReadOnlySpan<float> diffuse, ReadOnlySpan<float> specular,
        Span<float> f) =>
        throw new NotSupportedException($"{GetType().Name} takes no textures");

    /// <summary>The solid-angle density with which <see cref="Sample"/> draws <paramref name="wi"/>.</summary>
    public abstract float Pdf(Vector3 wo, Vector3 wi, Vector3 n);

    /// <summary>
    /// Draws ωi from the smooth lobes for the random numbers <paramref name="u"/> ∈ [0, 1)², with f(ωo, ωi) into
    /// <paramref name="f"/> (the estimator's weight is f·|cos θ_i|/pdf); false when it has no smooth lobe or the draw
    /// leaves the hemisphere.
    /// </summary>
    public abstract bool Sample(Vector3 wo, Vector3 n, Vector2 u, Span<float> f, out BsdfSample sample);

    /// <summary>
    /// The perfect mirror lobe: ωi = 2(n·ωo)n − ωo and its weight per band on the radiance arriving along it (k_r, times
    /// the Fresnel reflectance where the model has it, at band <paramref name="band"/>'s index; −1: every band).
    /// </summary>
    public virtual bool SampleMirror(Vector3 wo, Vector3 n, int band, Span<float> weight, out Vector3 wi)
    {
        wi = default;
        return false;
    }

    /// <summary>
    /// The specular transmission lobe: the refracted ωi at band <paramref name="band"/>'s index of refraction (−1: band 0's,
    /// for every band) and the weight per band on the radiance arriving along it (k_t, times 1 − Fresnel where the model has it).
    /// </summary>
    public virtual bool SampleTransmission(Vector3 wo, Vector3 n, int band, Span<float> weight, out Vector3 wi)
    {
        wi = default;
        return false;
    }

    /// <summary>
    /// The same BSDF with each of its spectra carried to another spectral grid by <paramref name="resample"/> (a scene
    /// spectrum's padded band values in, its values on that grid out): the path tracer's sub-band grid. Null when the model
    /// cannot be carried (the path tracer then refuses the material).
    /// </summary>
    public virtual Bsdf? Resampled(Func<float[], float[]> resample) => null;

    /// <summary>A unit direction about <paramref name="n"/> with density cos θ/π (Malley's method).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector3 CosineHemisphere(Vector3 n, Vector2 u)
    {
        float r = MathF.Sqrt(u.X), phi = 2 * MathF.PI * u.Y;
        float x = r * MathF.Cos(phi), y = r * MathF.Sin(phi), z = MathF.Sqrt(MathF.Max(0, 1 - u.X));
        var (t, b) = Frame(n);
        return x * t + y * b + z * n;
    }

    /// <summary>A unit direction about <paramref name="axis"/> with density (e + 1)/(2π)·cos^e α (a Phong lobe).</summary>
    public static Vector3 PowerCosine(Vector3 axis, Vector2 u, float exponent)
    {
        float cos = MathF.Pow(1 - u.X, 1 / (exponent + 1)), sin = MathF.Sqrt(MathF.Max(0, 1 - cos * cos));
        float phi = 2 * MathF.PI * u.Y;
        var (t, b) = Frame(axis);
        return sin * MathF.Cos(phi) * t + sin * MathF.Sin(phi) * b + cos * axis;
    }

    /// <summary>The density of <see cref="PowerCosine"/> at cos α.</summary>
    public static float PowerCosinePdf(float cos, float exponent) =>
        cos <= 0 ? 0 : (exponent + 1) / (2 * MathF.PI) * MathF.Pow(cos, exponent);

    /// <summary>An orthonormal basis (t, b) completing the unit vector n (Duff et al. 2017, branchless).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static (Vector3 T, Vector3 B) Frame(Vector3 n)
    {
        float sign = MathF.CopySign(1, n.Z);
        float a = -1 / (sign + n.Z), b = n.X * n.Y * a;
        return (new Vector3(1 + sign * n.X * n.X * a, sign * b, -sign * n.X), new Vector3(b, sign + n.Y * n.Y * a, -n.Y));
    }
}

/// <summary>
/// A Lambertian surface: f = ρ/π in every direction of the front hemisphere (ωo's side), drawn with density cos θ/π.
/// Its directional albedo is ρ at every angle of incidence.
/// </summary>
public sealed class LambertianBsdf(float[] reflectance) : Bsdf
{
    public float[] Reflectance { get; } = reflectance;

    public override BsdfFlags Lobes => BsdfFlags.Reflection | BsdfFlags.Diffuse;

    public override Bsdf Resampled(Func<float[], float[]> resample) => new LambertianBsdf(resample(Reflectance));

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public override void Evaluate(Vector3 wo, Vector3 wi, Vector3 n, Span<float> f)
    {
        float scale = SameSide(wo, wi, n) ? 1 / MathF.PI : 0;
        var rho = Reflectance.AsSpan(0, f.Length);
        int i = 0;
        if (Vector.IsHardwareAccelerated)
        {   // the same product per band, a SIMD register at a time (the path tracer's sub-band spectra are padded to whole registers)
            var fv = MemoryMarshal.Cast<float, Vector<float>>(f);
            var rv = MemoryMarshal.Cast<float, Vector<float>>(rho);
            var sv = new Vector<float>(scale);
            for (int k = 0; k < fv.Length; k++) fv[k] = rv[k] * sv;
            i = fv.Length * Vector<float>.Count;
        }
        for (; i < f.Length; i++) f[i] = rho[i] * scale;
    }

    public override bool TakesTextures => true;

    /// <summary>f = ρ_texel/π (a Lambertian surface has no specular weight).</summary>
    public override void Evaluate(Vector3 wo, Vector3 wi, Vector3 n, ReadOnlySpan<float> diffuse, ReadOnlySpan<float> specular,
        Span<float> f)
    {
        float scale = SameSide(wo, wi, n) ? 1 / MathF.PI : 0;
        var rho = diffuse.IsEmpty ? Reflectance.AsSpan(0, f.Length) : diffuse[..f.Length];
        for (int i = 0; i < f.Length; i++) f[i] = rho[i] * scale;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public override float Pdf(Vector3 wo, Vector3 wi, Vector3 n) => SameSide(wo, wi, n) ? MathF.Abs(Vector3.Dot(wi, n)) / MathF.PI : 0;

    public override bool Sample(Vector3 wo, Vector3 n, Vector2 u, Span<float> f, out BsdfSample sample)
    {
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        var wi = CosineHemisphere(front, u);
        sample = new BsdfSample(wi, Pdf(wo, wi, n), BsdfFlags.Reflection | BsdfFlags.Diffuse);
        Evaluate(wo, wi, n, f);
        return sample.Pdf > 0;
    }

    /// <summary>ωo and ωi on the same side of the surface (both strictly off it).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static bool SameSide(Vector3 wo, Vector3 wi, Vector3 n)
    {
        float a = Vector3.Dot(wo, n), b = Vector3.Dot(wi, n);
        return a > 0 ? b > 0 : a < 0 && b < 0;
    }
}
