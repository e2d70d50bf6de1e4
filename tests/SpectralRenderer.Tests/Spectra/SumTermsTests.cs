using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Spectra;

/// <summary>
/// SpectralMath.SumTerms (the packet path's one-pass sum of a lane's eq. 2 terms) against what the single-ray path does
/// with the same terms: Clear, then AddScaled / AddScaled2 in order — bit for bit, for 1 to 401 bands, with −0 and
/// negative factors, single and paired terms, and no term at all.
/// </summary>
public class SumTermsTests
{
    [Theory]
    [InlineData(1)]     // spectra of 1, 2, 3 and 4 SIMD vectors (8-float vectors: 1, 13, 20, 29 bands + 3 colour lanes) are
    [InlineData(13)]    // summed in registers, longer ones in memory: each of those paths against the reference
    [InlineData(20)]
    [InlineData(29)]
    [InlineData(30)]
    [InlineData(401)]
    public void Summing_the_listed_terms_is_clearing_and_adding_them_in_order_bit_for_bit(int bands)
    {
        int padded = SpectralMath.Padded(bands);
        var r = new Random(bands);
        const int tables = 6;
        var flat = new float[tables * padded];
        for (int i = 0; i < flat.Length; i++) flat[i] = i % 37 == 0 ? -0f : (float)(r.NextDouble() * 3 - 0.5);
        float[] factors = [1f, 0.3f, -0f, 2.5e-7f, -1.25f, 0f];
        for (int n = 0; n < 400; n++)
        {
            int count = n % 6;
            var terms = new SpectralTerm[count];
            for (int j = 0; j < count; j++)
            {
                int a = r.Next(tables) * padded, b = r.Next(tables) * padded;
                float s = factors[r.Next(factors.Length)] * (float)(0.5 + r.NextDouble()), t = factors[r.Next(factors.Length)];
                terms[j] = r.Next(2) == 0 ? new SpectralTerm(a, s) : new SpectralTerm(a, s, b, t);
            }
            var expected = new float[padded];
            Array.Fill(expected, float.NaN);
            SpectralMath.Clear(expected);
            foreach (var term in terms)
                if (term.B < 0) SpectralMath.AddScaled(expected, flat.AsSpan(term.A, padded), term.S);
                else SpectralMath.AddScaled2(expected, flat.AsSpan(term.A, padded), term.S, flat.AsSpan(term.B, padded), term.T);
            var actual = new float[padded];
            Array.Fill(actual, float.NaN);   // every value is written
            SpectralMath.SumTerms(actual, flat, terms);
            for (int i = 0; i < padded; i++)
                Assert.True(BitConverter.SingleToInt32Bits(expected[i]) == BitConverter.SingleToInt32Bits(actual[i]),
                    $"case {n}, {count} terms, value {i}: {expected[i]:R} vs {actual[i]:R}");
        }
    }

    [Fact]
    public void TermPastTheTablesIsRefused()
    {
        // The sum reads without bounds checks, so a term whose spectrum would run past the tables must be refused first.
        int padded = System.Numerics.Vector<float>.Count * 2;
        var flat = new float[3 * padded];
        var dst = new float[padded];
        SpectralMath.SumTerms(dst, flat, [new SpectralTerm(2 * padded, 1f, 0, 1f)]);   // the last table: fine
        Assert.Throws<ArgumentOutOfRangeException>(() => SpectralMath.SumTerms(dst, flat, [new SpectralTerm(2 * padded + 1, 1f)]));
        Assert.Throws<ArgumentOutOfRangeException>(() => SpectralMath.SumTerms(dst, flat, [new SpectralTerm(0, 1f, 2 * padded + 1, 1f)]));
        Assert.Throws<ArgumentOutOfRangeException>(() => SpectralMath.SumTerms(dst, flat, [new SpectralTerm(-1, 1f)]));
        // Tables shorter than one spectrum: no offset fits.
        Assert.Throws<ArgumentOutOfRangeException>(() => SpectralMath.SumTerms(dst, new float[padded - 1], [new SpectralTerm(0, 1f)]));
    }
}
