using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>
/// Deterministic random numbers in [0, 1) for one camera sample, from (pixel x, pixel y, sample index, dimension) only,
/// so a pixel's value does not depend on the thread, the tile order or the shard that traces it. <see
/// cref="SamplerKind.Independent"/>: dimensions 0 and 1 are the film jitter (<see cref="Renderer"/>'s <c>Hash(x, y, s)</c>
/// split in its 16-bit halves, as every render before it used); each later dimension is its own counter-based hash of the
/// sample and the dimension. <see cref="SamplerKind.Sobol"/>: each 2D draw is a pair of Owen-scrambled Sobol dimensions and
/// each 1D draw an Owen-scrambled van der Corput dimension (<see cref="OwenSobol"/>), seeded per (pixel, dimension, seed)
/// and per randomisation: sample s belongs to randomisation g = s mod <see cref="Randomisations"/> and is point s div
/// <see cref="Randomisations"/> of that randomisation's own scrambled sequence, so a pixel's samples are
/// <see cref="Randomisations"/> independent randomised quasi-Monte Carlo estimates, interleaved, whose spread gives the
/// pixel's standard error (Owen 1997; L'Ecuyer &amp; Lemieux 2002, §3; <c>Renderer.Statistics.cs</c>).
/// </summary>
public struct Sampler(int x, int y, int sample, int dimension = 0, SamplerSettings settings = default)
{
    /// <summary>
    /// The independent randomisations (scrambles) of the Sobol sequence a pixel's samples are spread over, sample s in
    /// randomisation s mod R: their means are independent and identically distributed, so the spread of R means estimates
    /// the variance of their average without bias (R − 1 degrees of freedom), which one scrambled net cannot.
    /// </summary>
    public const int Randomisations = 8;

    readonly uint _x = (uint)x, _y = (uint)y, _s = (uint)sample;
    // The Sobol draws' shuffle starts from R(index within the randomisation); the independent sampler never reads it (a
    // camera ray's jitter is one hash).
    readonly uint _sReversed = settings.Kind == SamplerKind.Sobol ? OwenSobol.ReverseBits((uint)sample / (uint)Randomisations) : 0;
    // The randomisation's own scramble: its index mixed into every dimension's seed (0: the pixel's seeds as they were).
    readonly uint _group = settings.Kind == SamplerKind.Sobol ? (uint)sample % (uint)Randomisations * 0x27D4EB2Fu : 0;
    readonly SamplerSettings _settings = settings;

    /// <summary>The next dimension to be drawn.</summary>
    public int Dimension { readonly get; private set; } = dimension;

    /// <summary>The next two dimensions: at dimension 0 the film jitter (16-bit resolution), later two 1D draws.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public (float U, float V) Next2D()
    {
        if (_settings.Kind == SamplerKind.Sobol)
        {
            uint d = (uint)Dimension;
            Dimension += 2;
            return OwenSobol.Sample2DReversed(_sReversed, PixelSeed(d));
        }
        if (Dimension == 0)
        {
            Dimension = 2;
            uint h = Renderer.Hash(_x, _y + _settings.Seed * 0x632BE5ABu, _s);
            return ((h & 0xFFFF) / 65536f, (h >> 16) / 65536f);
        }
        float u = Next1D();
        return (u, Next1D());
    }

    /// <summary>The next dimension: 24 random bits of a hash of the sample and the dimension.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float Next1D() => At1D(Reserve1D());

    /// <summary>
    /// The next 1D dimension, taken without drawing it: an integrator that may not need a number (a lobe choice with one
    /// lobe, Russian roulette before its depth) reserves its dimension and draws it with <see cref="At1D"/> only when needed,
    /// so the dimensions after it, and every number drawn, are the same as if it had been drawn.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public int Reserve1D()
    {
        if (_settings.Kind != SamplerKind.Sobol && Dimension < 2) Dimension = 2;   // 0 and 1 are the film jitter's
        return Dimension++;
    }

    /// <summary>The next two dimensions as <see cref="Reserve1D"/> does (drawn by <see cref="At2D"/>); not the film jitter's.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public int Reserve2D()
    {
        if (_settings.Kind != SamplerKind.Sobol && Dimension < 2) Dimension = 2;
        int d = Dimension;
        Dimension += 2;
        return d;
    }

    /// <summary>The value of 1D dimension <paramref name="dimension"/> (from <see cref="Reserve1D"/>) of this sample.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public readonly float At1D(int dimension)
    {
        if (_settings.Kind == SamplerKind.Sobol) return OwenSobol.Sample1DReversed(_sReversed, PixelSeed((uint)dimension));
        uint h = Renderer.Hash(_x, _y + _settings.Seed * 0x632BE5ABu, _s) ^ (uint)dimension * 0x9E3779B9u;
        // lowbias32 again (C. Wellons): every input bit reaches every output bit.
        h ^= h >> 16; h *= 0x7FEB352Du; h ^= h >> 15; h *= 0x846CA68Bu; h ^= h >> 16;
        return (h >> 8) * (1f / (1 << 24));
    }

    /// <summary>The value of the 2D dimension pair <paramref name="dimension"/> (from <see cref="Reserve2D"/>), as <see cref="Next2D"/>
    /// draws it there.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public readonly (float U, float V) At2D(int dimension) =>
        _settings.Kind == SamplerKind.Sobol
            ? OwenSobol.Sample2DReversed(_sReversed, PixelSeed((uint)dimension))
            : (At1D(dimension), At1D(dimension + 1));

    /// <summary>The scramble seed of dimension <paramref name="d"/> of this pixel and the sample's randomisation (the index
    /// within the randomisation is not in it: each randomisation's samples are one scrambled sequence).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    readonly uint PixelSeed(uint d) => Renderer.Hash(_x, _y ^ _group, d ^ _settings.Seed * 0x632BE5ABu);
}

/// <summary>
/// One camera sample of a pixel, as the <see cref="Renderer"/> hands it to an integrator: the pixel (film coordinates),
/// the sample index (<see cref="Centre"/> for the pixel-centre ray of the analysis images), the camera ray through its
/// film position, and the sampler for the integrator's further random numbers (its first two dimensions are the jitter).
/// </summary>
public readonly struct CameraSample(int x, int y, int index, Ray ray, SamplerSettings sampler = default)
{
    /// <summary>The sample index of the unjittered ray through the pixel centre.</summary>
    public const int Centre = -1;

    public int X { get; } = x;
    public int Y { get; } = y;
    public int Index { get; } = index;
    public Ray Ray { get; } = ray;
    /// <summary>The render's sampler (kind and seed).</summary>
    public SamplerSettings Settings { get; } = sampler;

    /// <summary>The sample's random numbers after the film jitter (dimension 2 on).</summary>
    public Sampler Sampler => new(X, Y, Index, 2, Settings);
}
