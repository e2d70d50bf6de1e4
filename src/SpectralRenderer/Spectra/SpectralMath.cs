using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Runtime.Intrinsics;

namespace SpectralRenderer.Spectra;

/// <summary>
/// Band-wise arithmetic on spectra held as float spans whose length is padded to a multiple of
/// <see cref="Vector{T}.Count"/>, so every operation runs as whole SIMD vectors.
/// </summary>
public static class SpectralMath
{
    /// <summary>
    /// Lanes after the bands that carry a radiance's colour, X, Y, Z (κ included), through every operation: a term of
    /// eq. 2 adds its table's exact XYZ there while its band values go in the bands, so a pixel's colour is exact at the
    /// tables' full resolution (exact band integration). Lane <c>bands + 0</c> is X, <c>+ 1</c> Y, <c>+ 2</c> Z.
    /// </summary>
    public const int ColourLanes = 3;

    /// <summary>The padded length for <paramref name="bands"/> bands and the <see cref="ColourLanes"/> after them.</summary>
    public static int Padded(int bands) => (bands + ColourLanes + Vector<float>.Count - 1) / Vector<float>.Count * Vector<float>.Count;

    /// <summary>Pads band values (double) to a SIMD-ready float array.</summary>
    public static float[] ToPadded(ReadOnlySpan<double> values)
    {
        var a = new float[Padded(values.Length)];
        for (int i = 0; i < values.Length; i++) a[i] = (float)values[i];
        return a;
    }

    static Span<Vector<float>> V(Span<float> s) => MemoryMarshal.Cast<float, Vector<float>>(s);
    static ReadOnlySpan<Vector<float>> V(ReadOnlySpan<float> s) => MemoryMarshal.Cast<float, Vector<float>>(s);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Clear(Span<float> dst) => dst.Clear();

    /// <summary>dst += a ⊙ b · s</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void AddProduct(Span<float> dst, ReadOnlySpan<float> a, ReadOnlySpan<float> b, float s)
    {
        var d = V(dst); var va = V(a); var vb = V(b);
        var vs = new Vector<float>(s);
        for (int i = 0; i < d.Length; i++) d[i] += va[i] * vb[i] * vs;
    }

    /// <summary>dst += a ⊙ (b·s + c·t): the diffuse and specular terms of eq. 2 in one pass.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void AddProduct2(Span<float> dst, ReadOnlySpan<float> a, ReadOnlySpan<float> b, float s, ReadOnlySpan<float> c, float t)
    {
        var d = V(dst); var va = V(a); var vb = V(b); var vc = V(c);
        var vs = new Vector<float>(s); var vt = new Vector<float>(t);
        for (int i = 0; i < d.Length; i++) d[i] += va[i] * (vb[i] * vs + vc[i] * vt);
    }

    /// <summary>dst += a ⊙ b</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void AddProduct(Span<float> dst, ReadOnlySpan<float> a, ReadOnlySpan<float> b)
    {
        var d = V(dst); var va = V(a); var vb = V(b);
        for (int i = 0; i < d.Length; i++) d[i] += va[i] * vb[i];
    }

    /// <summary>dst += a·s + b·t: the diffuse and specular terms of eq. 2 from their precomputed tables.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void AddScaled2(Span<float> dst, ReadOnlySpan<float> a, float s, ReadOnlySpan<float> b, float t)
    {
        var d = V(dst); var va = V(a); var vb = V(b);
        var vs = new Vector<float>(s); var vt = new Vector<float>(t);
        for (int i = 0; i < d.Length; i++) d[i] += va[i] * vs + vb[i] * vt;
    }

    /// <summary>
    /// dst = (((0 + term₁) + term₂) + …) in the order given, each term a·s or (a·s + b·t) with a, b the padded spectra at
    /// offsets <see cref="SpectralTerm.A"/>, <see cref="SpectralTerm.B"/> of <paramref name="tables"/>: band for band exactly
    /// what <see cref="Clear"/> and then <see cref="AddScaled"/> / <see cref="AddScaled2"/> in that order leave, without the
    /// clearing pass (the first term is written, not added).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void SumTerms(Span<float> dst, ReadOnlySpan<float> tables, ReadOnlySpan<SpectralTerm> terms)
    {
        var d = V(dst);
        if (terms.IsEmpty) { dst.Clear(); return; }
        int n = d.Length;
        if (n <= SmallVectors) { SumTermsSmall(dst, tables, terms); return; }
        for (int j = 0; j < terms.Length; j++)
        {
            var term = terms[j];
            var va = V(tables.Slice(term.A, dst.Length));
            var vs = new Vector<float>(term.S);
            // The first term lands on +0 (as on a cleared spectrum: 0 + (−0) = +0), the others on the sum so far.
            if (term.B < 0)
            {
                if (j == 0) for (int i = 0; i < n; i++) d[i] = Vector<float>.Zero + va[i] * vs;
                else for (int i = 0; i < n; i++) d[i] += va[i] * vs;
            }
            else
            {
                var vb = V(tables.Slice(term.B, dst.Length));
                var vt = new Vector<float>(term.T);
                if (j == 0) for (int i = 0; i < n; i++) d[i] = Vector<float>.Zero + (va[i] * vs + vb[i] * vt);
                else for (int i = 0; i < n; i++) d[i] += va[i] * vs + vb[i] * vt;
            }
        }
    }

    /// <summary>Spectra of at most this many SIMD vectors (the paper's 20 bands and its colour lanes: 3 of 8 floats) are summed
    /// in registers by <see cref="SumTermsSmall"/>.</summary>
    const int SmallVectors = 4;

    /// <summary>
    /// <see cref="SumTerms"/> for a spectrum of at most <see cref="SmallVectors"/> vectors: each vector's sum stays in a register
    /// from term to term and is stored once (the same additions in the same order, so the same bits). The terms' offsets are
    /// checked against the tables once, before the unchecked loads.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    static void SumTermsSmall(Span<float> dst, ReadOnlySpan<float> tables, ReadOnlySpan<SpectralTerm> terms)
    {
        int w = Vector<float>.Count, n = dst.Length / w, last = tables.Length - dst.Length;
        if (last < 0) throw new ArgumentOutOfRangeException(nameof(tables));   // no spectrum fits in the tables
        foreach (ref readonly var term in terms)
            if ((uint)term.A > (uint)last || (term.B >= 0 && term.B > last)) throw new ArgumentOutOfRangeException(nameof(terms));
        ref float t = ref MemoryMarshal.GetReference(tables);
        // The first term lands on +0 (0 + (−0) = +0), as on a cleared spectrum.
        Vector<float> s0 = Vector<float>.Zero, s1 = Vector<float>.Zero, s2 = Vector<float>.Zero, s3 = Vector<float>.Zero;
        foreach (ref readonly var term in terms)
        {
            ref float a = ref Unsafe.Add(ref t, term.A);
            var vs = new Vector<float>(term.S);
            if (term.B < 0)
            {
                s0 += Vector.LoadUnsafe(ref a) * vs;
                if (n > 1) s1 += Vector.LoadUnsafe(ref a, (nuint)w) * vs;
                if (n > 2) s2 += Vector.LoadUnsafe(ref a, (nuint)(2 * w)) * vs;
                if (n > 3) s3 += Vector.LoadUnsafe(ref a, (nuint)(3 * w)) * vs;
            }
            else
            {
                ref float b = ref Unsafe.Add(ref t, term.B);
                var vt = new Vector<float>(term.T);
                s0 += Vector.LoadUnsafe(ref a) * vs + Vector.LoadUnsafe(ref b) * vt;
                if (n > 1) s1 += Vector.LoadUnsafe(ref a, (nuint)w) * vs + Vector.LoadUnsafe(ref b, (nuint)w) * vt;
                if (n > 2) s2 += Vector.LoadUnsafe(ref a, (nuint)(2 * w)) * vs + Vector.LoadUnsafe(ref b, (nuint)(2 * w)) * vt;
                if (n > 3) s3 += Vector.LoadUnsafe(ref a, (nuint)(3 * w)) * vs + Vector.LoadUnsafe(ref b, (nuint)(3 * w)) * vt;
            }
        }
        ref float d = ref MemoryMarshal.GetReference(dst);
        s0.StoreUnsafe(ref d);
        if (n > 1) s1.StoreUnsafe(ref d, (nuint)w);
        if (n > 2) s2.StoreUnsafe(ref d, (nuint)(2 * w));
        if (n > 3) s3.StoreUnsafe(ref d, (nuint)(3 * w));
    }

    /// <summary>dst = 0 + a · s: band for band what <see cref="Clear"/> and then <see cref="AddScaled"/> leave (0 + (−0) = +0), in one
    /// pass.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void SetScaled(Span<float> dst, ReadOnlySpan<float> a, float s)
    {
        var d = V(dst); var va = V(a);
        var vs = new Vector<float>(s);
        for (int i = 0; i < d.Length; i++) d[i] = Vector<float>.Zero + va[i] * vs;
    }

    /// <summary>dst += a · s</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void AddScaled(Span<float> dst, ReadOnlySpan<float> a, float s)
    {
        var d = V(dst); var va = V(a);
        var vs = new Vector<float>(s);
        for (int i = 0; i < d.Length; i++) d[i] += va[i] * vs;
    }

    /// <summary>True when any band is non-zero.</summary>
    public static bool Any(ReadOnlySpan<float> a)
    {
        foreach (var v in V(a)) if (!Vector.EqualsAll(v, Vector<float>.Zero)) return true;
        return false;
    }

    /// <summary>The first dst.Length values of a padded spectrum into dst, in whole vectors (the last one overlapping) when dst holds at
    /// least one.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void CopyBands(ReadOnlySpan<float> padded, Span<float> dst)
    {
        int n = dst.Length, w = Vector<float>.Count;
        if (n < w || padded.Length < n) { padded[..n].CopyTo(dst); return; }
        ref float s = ref MemoryMarshal.GetReference(padded);
        ref float d = ref MemoryMarshal.GetReference(dst);
        int i = 0;
        for (; i + w <= n; i += w) Vector.StoreUnsafe(Vector.LoadUnsafe(ref s, (nuint)i), ref d, (nuint)i);
        if (i < n) Vector.StoreUnsafe(Vector.LoadUnsafe(ref s, (nuint)(n - w)), ref d, (nuint)(n - w));
    }

    /// <summary>Below this many bands a pixel spans too few whole cache lines for <see cref="StreamBands"/> to pay.</summary>
    public const int StreamMinBands = 128;

    /// <summary>
    /// As <see cref="CopyBands"/> into a framebuffer far larger than the caches, for a pixel of at least
    /// <see cref="StreamMinBands"/> bands: the whole cache lines of the destination are written with non-temporal
    /// (streaming) stores, which skip reading each line before writing it (half the memory traffic of a plain store),
    /// the ragged ends with plain stores. The caller issues <see cref="StreamFence"/> before another thread reads the
    /// pixels. The same values as <see cref="CopyBands"/>, bit for bit.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static unsafe void StreamBands(ReadOnlySpan<float> padded, Span<float> dst)
    {
        int n = dst.Length;
        if (n < StreamMinBands || padded.Length < n || !Vector256.IsHardwareAccelerated) { CopyBands(padded, dst); return; }
        fixed (float* d0 = dst)
        fixed (float* s0 = padded)
        {
            // Plain stores up to the first 64-byte boundary and from the last one; streaming stores between them.
            int head = (int)(((64 - ((nuint)d0 & 63)) & 63) / sizeof(float));
            int body = (n - head) & ~15;
            if (body <= 0) { CopyBands(padded, dst); return; }
            for (int i = 0; i < head; i++) d0[i] = s0[i];
            float* d = d0 + head, s = s0 + head;
            if (Vector512.IsHardwareAccelerated)
                for (int i = 0; i < body; i += 16) Vector512.StoreAlignedNonTemporal(Vector512.Load(s + i), d + i);
            else
                for (int i = 0; i < body; i += 8) Vector256.StoreAlignedNonTemporal(Vector256.Load(s + i), d + i);
            for (int i = head + body; i < n; i++) d0[i] = s0[i];
        }
    }

    /// <summary>Orders the streaming stores of <see cref="StreamBands"/> before every later store (x86 sfence), so a
    /// thread that sees what follows sees the pixels.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void StreamFence()
    {
        if (System.Runtime.Intrinsics.X86.Sse.IsSupported) System.Runtime.Intrinsics.X86.Sse.StoreFence();
    }
}

/// <summary>
/// One term of <see cref="SpectralMath.SumTerms"/>: the padded spectrum at offset <see cref="A"/> of a flat table array
/// times <see cref="S"/>, plus (when <see cref="B"/> ≥ 0) the one at <see cref="B"/> times <see cref="T"/>.
/// </summary>
public readonly record struct SpectralTerm(int A, float S, int B = -1, float T = 0);
