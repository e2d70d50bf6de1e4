using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

/// <summary>
/// A fluorescent material's shifted diffuse lobe on the path tracer's fine grid (<see cref="FineGrid"/>): the re-radiation
/// matrix's off-diagonal part as S[o, i]/π (a Lambertian re-emission, 1/sr) integrated exactly over sub-band × sub-band
/// (<see cref="ReradiationMatrix.ShiftOnBands(int, Func{int, double}, Func{int, double})"/>), beside the reflective diagonal
/// that the material's BSDF already carries. Next-event estimation adds β ⊙ (S·L_e) for the light sample (a delta light, an
/// emitter's point or a sky direction) at full weight: the shift is excited by direct light only. Light reaching the surface
/// after another bounce would need the throughput to become a matrix (camera wavelength × current wavelength); it excites
/// only the reflective diagonal, which the path's β carries as for any material. One N × N product per light sample.
/// </summary>
sealed class FluorescentShift
{
    readonly float[] _s;   // [o * n + i], 1/π folded in
    readonly int _n;

    public FluorescentShift(ReradiationMatrix matrix, FineGrid grid)
    {
        _n = grid.Count;
        var s = matrix.ShiftOnBands(_n, f => grid.Lower[f], f => grid.Upper[f]);
        _s = new float[_n * _n];
        for (int k = 0; k < s.Length; k++) _s[k] = (float)(s[k] / Math.PI);
    }

    /// <summary>Whether wi leaves on the side wo arrives from (the diffuse lobe's hemisphere, as <c>Eq2Bsdf</c> decides it).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static bool Reflects(Vector3 wo, Vector3 wi, Vector3 n)
    {
        var front = Vector3.Dot(wo, n) >= 0 ? n : -n;
        return Vector3.Dot(front, wi) > 0 && Vector3.Dot(front, wo) > 0;
    }

    /// <summary>l[o] += β[o]·Σ_i S[o, i]·radiance[i]·scale.</summary>
    public void AddEmitted(Span<float> l, ReadOnlySpan<float> beta, ReadOnlySpan<float> radiance, float scale)
    {
        for (int o = 0; o < _n; o++)
        {
            if (beta[o] == 0) continue;
            var row = _s.AsSpan(o * _n, _n);
            float sum = 0;
            for (int i = 0; i < row.Length; i++) sum += row[i] * radiance[i];
            l[o] += beta[o] * sum * scale;
        }
    }
}
