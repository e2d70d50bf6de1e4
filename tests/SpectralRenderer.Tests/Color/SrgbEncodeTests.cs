using SpectralRenderer.Color;

namespace SpectralRenderer.Tests.Color;

/// <summary>The table-driven 8-bit encode gives exactly the bytes of the IEC 61966-2-1 formula, To8(Encode(x)).</summary>
public class SrgbEncodeTests
{
    static byte Reference(RgbSpace space, double x) => RgbSpace.To8(space.Encode(x));

    static void Same(RgbSpace space, double x) =>
        Assert.True(Reference(space, x) == space.Encode8(x),
            $"{space.Name} {x:R} ({BitConverter.DoubleToInt64Bits(x):x}): table {space.Encode8(x)}, formula {Reference(space, x)}");

    /// <summary>The least double in [0, 1] the formula codes at k or above, by bisection over the bit patterns (positive doubles order as
    /// their bits).</summary>
    static double Boundary(int k)
    {
        long lo = 0, hi = BitConverter.DoubleToInt64Bits(1.0);
        while (lo < hi)
        {
            long mid = lo + (hi - lo) / 2;
            if (Reference(RgbSpace.Srgb, BitConverter.Int64BitsToDouble(mid)) >= k) hi = mid; else lo = mid + 1;
        }
        return BitConverter.Int64BitsToDouble(lo);
    }

    [Fact]
    public void Every_code_boundary_and_64_ulps_either_side_match_the_formula()
    {
        double previous = 0;
        for (int k = 1; k <= 255; k++)
        {
            double t = Boundary(k);
            Assert.True(t > previous, $"boundary {k} at {t:R} is not above boundary {k - 1}");
            previous = t;
            Assert.Equal(k, RgbSpace.Srgb.Encode8(t));
            Assert.Equal(k - 1, RgbSpace.Srgb.Encode8(Math.BitDecrement(t)));
            double x = t;
            for (int u = 0; u < 64; u++, x = Math.BitIncrement(x)) Same(RgbSpace.Srgb, x);
            x = t;
            for (int u = 0; u < 64; u++, x = Math.BitDecrement(x)) Same(RgbSpace.Srgb, x);
        }
        Assert.InRange(Boundary(1), 1e-4, 2e-4);     // 0.5 / 255 / 12.92 ≈ 1.518e-4, on the linear segment
        Assert.InRange(Boundary(255), 0.99, 1.0);
    }

    [Fact]
    [Trait("Category", "Slow")]
    public void A_million_random_values_special_values_and_bucket_edges_match_the_formula()
    {
        var rng = new Random(2024);
        foreach (var space in new[] { RgbSpace.Srgb, RgbSpace.Paper })
        {
            for (int i = 0; i < 500_000; i++) Same(space, -0.1 + 1.2 * rng.NextDouble());
            for (int i = 0; i < 500_000; i++)   // any bit pattern below 1: tiny values as often as large ones
                Same(space, BitConverter.Int64BitsToDouble(rng.NextInt64(0, BitConverter.DoubleToInt64Bits(1.0))));
            foreach (double x in new[] { double.NaN, double.NegativeInfinity, double.PositiveInfinity, -0.0, 0.0, double.Epsilon,
                         1.0, Math.BitDecrement(1.0), Math.BitIncrement(1.0), 0.0031308, Math.BitIncrement(0.0031308),
                             Math.BitDecrement(0.0031308), -1e-300, 7.5 })
                Same(space, x);
            for (int i = 0; i <= 4096; i++)
            {
                double edge = i / 4096.0;
                Same(space, edge); Same(space, Math.BitDecrement(edge)); Same(space, Math.BitIncrement(edge));
            }
        }
        Assert.Equal(0, RgbSpace.Srgb.Encode8(double.NaN));
        Assert.Equal(255, RgbSpace.Srgb.Encode8(2.0));
        Assert.Equal(188, RgbSpace.Srgb.Encode8(0.5));   // 1.055 · 0.5^(1/2.4) − 0.055 = 0.7354 → 187.5… → 188
        Assert.Equal(128, RgbSpace.Paper.Encode8(0.5));  // no curve: round(127.5) away from zero
    }
}
