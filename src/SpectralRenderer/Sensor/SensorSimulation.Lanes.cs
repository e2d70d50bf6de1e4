using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;

namespace SpectralRenderer.Sensor;

public static partial class SensorSimulation
{
    /// <summary>
    /// The read-out of <see cref="Readout.Photosite"/> for eight consecutive photosites of row y at once, in AVX-512
    /// lanes: their streams' hashes, PRNU and DSNU, the Poisson count (<see cref="NoiseLanes.Poisson"/>), the
    /// ziggurat's rectangle for the read noise, gain and ADC. Each lane does the scalar code's IEEE operations in its
    /// order (no fused multiply-add; the same vectorised ln and exp), so a decided lane holds the scalar result bit for
    /// bit; a lane where a step did not decide (a ziggurat wedge or tail, about 1 %; PTRS in the rare cases
    /// <see cref="NoiseLanes.Poisson"/> leaves) is redone by <see cref="Readout.Photosite"/>. Returns how many of the row's flat
    /// indices it did (whole groups of eight); the caller does the rest one by one.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static int ExposeLanes(Readout r, int[] pixelOf, ReadOnlySpan<int> channels, ReadOnlySpan<double> te, int w, int y, float[] dn)
    {
        int n = channels.Length, rowStart = y * n, j = 0;
        long rowPixel = (long)y * w;
        var zero = Vector512<double>.Zero;
        var one = Vector512.Create(1.0);
        for (; j + 8 <= n; j += 8)
        {
            var pixels = Vector256.Create<int>(pixelOf.AsSpan(j, 8));
            var pixel = Vector512.Create((ulong)rowPixel)
                + Vector512.Create(Vector256.WidenLower(pixels), Vector256.WidenUpper(pixels)).AsUInt64();
            var chans = Vector256.Create<int>(channels.Slice(j, 8));
            var channel = Vector512.Create(Vector256.WidenLower(chans), Vector256.WidenUpper(chans)).AsUInt64();
            var t = Vector512.Create<double>(te.Slice(j, 8));
            var rates = Vector256.Create<float>(dn.AsSpan(rowStart + j, 8));
            var mean = Vector512.Create(Vector256.WidenLower(rates), Vector256.WidenUpper(rates)) * t;

            var decided = Vector512<double>.AllBitsSet;
            Vector512<double> gain = one, offset = zero;
            if (r.Prnu > 0)
            {
                var z = NoiseLanes.Normal(NoiseLanes.Keys(r.PrnuFamily, pixel, channel), Vector512<ulong>.Zero, out var d);
                gain = Vector512.Max(zero, one + Vector512.Create(r.Prnu) * z);
                decided &= d;
            }
            if (r.Dsnu > 0)
            {
                var z = NoiseLanes.Normal(NoiseLanes.Keys(r.DsnuFamily, pixel, channel), Vector512<ulong>.Zero, out var d);
                offset = Vector512.Create(r.Dsnu) * z;
                decided &= d;
            }
            var keys = NoiseLanes.Keys(r.Temporal, pixel, channel);
            var k = NoiseLanes.Poisson(keys, mean * gain + Vector512.Create(r.Dark) * t, out var next, out var dp);
            var read = NoiseLanes.Normal(keys, next, out var dr);
            decided &= dp & dr;
            var electrons = Vector512.Min(k, Vector512.Create(r.FullWell));
            var volts = electrons * Vector512.Create(r.ConversionGain) + offset + Vector512.Create(r.Read) * read;
            var x = Vector512.Create(r.Black) + volts * Vector512.Create(r.VoltToDn);
            var q = Vector512.Min(Vector512.Floor(Vector512.Max(x, zero) + Vector512.Create(HalfBelow)), Vector512.Create(r.White));
            var result = Vector256.Narrow(q.GetLower(), q.GetUpper());

            ulong mask = decided.ExtractMostSignificantBits();
            if (mask == 0xFF) { result.CopyTo(dn, rowStart + j); continue; }
            for (int l = 0; l < 8; l++)
            {
                int i = rowStart + j + l;
                dn[i] =
                    (mask >> l & 1) != 0 ? result.GetElement(l) : r.Photosite(dn[i], te[j + l], rowPixel + pixelOf[j + l], channels[j + l]);
            }
        }
        return j;
    }
}
