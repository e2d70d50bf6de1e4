using System.Runtime.Intrinsics;
using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Sensor;

/// <summary>
/// The sensor's 8-lane read-out against the photosite-by-photosite one (a second computation of the same model):
/// bit-identical raw frames for every arrangement, across means from below 1 e⁻ to past the full well, with and
/// without fixed-pattern noise, and lane streams equal to the scalar streams.
/// </summary>
public class SensorLanesTests(Xunit.Abstractions.ITestOutputHelper output)
{
    [SkippableFact]
    public void NoiseLanes_AreTheScalarStreams_LaneByLane()
    {
        Skip.IfNot(Vector512.IsHardwareAccelerated, "no AVX-512 here: the sensor runs photosite by photosite only");
        ulong family = NoiseStream.Family(5, 3);
        int decided = 0, total = 0;
        for (long p0 = 0; p0 < 40_000; p0 += 8)
        {
            var pixel = Vector512.Create((ulong)p0) + Vector512.Create(0UL, 1, 2, 3, 4, 5, 6, 7);
            var channel = Vector512.Create(0UL, 1, 2, 3, 0, 1, 2, 15);
            var keys = NoiseLanes.Keys(family, pixel, channel);
            var u0 = NoiseLanes.Uniform(keys, Vector512<ulong>.Zero);
            var u1 = NoiseLanes.Uniform(keys, Vector512<ulong>.One);
            var z = NoiseLanes.Normal(keys, Vector512.Create(2UL), out var ok);
            for (int l = 0; l < 8; l++)
            {
                var s = new NoiseStream(family, p0 + l, (int)channel.GetElement(l));
                Assert.Equal(s.Uniform(), u0.GetElement(l));
                Assert.Equal(s.Uniform(), u1.GetElement(l));
                double scalar = s.Normal();
                total++;
                if (ok.GetElement(l) != 0) { decided++; Assert.Equal(scalar, z.GetElement(l)); }
            }
        }
        output.WriteLine($"ziggurat rectangle decided {decided} of {total} lanes");
        Assert.InRange(decided / (double)total, 0.985, 0.995);   // 1 − (wedges + tail) ≈ 0.9897 for 256 layers
    }

    [SkippableFact]
    public void PoissonLanes_AreTheScalarSampler_LaneByLane_WithTheNextDraw()
    {
        Skip.IfNot(Vector512.IsHardwareAccelerated, "no AVX-512 here: the sensor runs photosite by photosite only");
        ulong family = NoiseStream.Family(8, 3);
        var mus = Vector512.Create(0.0, 0.3, 9.99, 10, 15.5, 40, 1000, 8000);
        int decided = 0, total = 0;
        for (long p0 = 0; p0 < 80_000; p0 += 8)
        {
            var keys =
                NoiseLanes.Keys(family, Vector512.Create((ulong)p0) + Vector512.Create(0UL, 1, 2, 3, 4, 5, 6, 7), Vector512<ulong>.Zero);
            var k = NoiseLanes.Poisson(keys, mus, out var next, out var ok);
            var z = NoiseLanes.Normal(keys, next, out var zok);
            for (int l = 0; l < 8; l++)
            {
                total++;
                if (ok.GetElement(l) == 0) continue;
                decided++;
                var s = new NoiseStream(family, p0 + l, 0);
                Assert.Equal(s.Poisson(mus.GetElement(l)), k.GetElement(l));
                double scalarNext = s.Normal();   // the draw after the count: the same stream position as the lanes' next
                if (zok.GetElement(l) != 0) Assert.Equal(scalarNext, z.GetElement(l));
            }
        }
        output.WriteLine($"Poisson lanes decided {decided} of {total}");
        Assert.True(decided > 0.99 * total);
    }

    /// <summary>A cube of 37 × 13 pixels (rows not a multiple of the 8 lanes), radiance falling by e¹² across it, spectrally
    /// varied.</summary>
    static RadianceCube Cube()
    {
        const int w = 37, h = 13;
        var grid = new BandGrid(380, 780, 20);
        var data = new float[w * h * grid.Count];
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                for (int b = 0; b < grid.Count; b++)
                    data[(y * w + x) * grid.Count + b] = (float)(Math.Exp(-12.0 * (x + y * w) / (w * h)) * (1 + 0.5 * Math.Sin(b + x)));
        return new RadianceCube(w, h, grid, data, 1);
    }

    [SkippableTheory]
    [InlineData("nikon-d5100", false)]
    [InlineData("mosaic-16", false)]
    [InlineData("cie-xyz", false)]
    [InlineData("wheel-6", false)]
    [InlineData("sigma-sd-merrill", true)]
    [InlineData("sigma-sd-merrill-x3", true)]
    [InlineData("isetcam", true)]
    public void LanesAndPhotositeByPhotosite_GiveTheSameRawBits(string name, bool fixedPattern)
    {
        Skip.IfNot(Vector512.IsHardwareAccelerated, "no AVX-512 here: the sensor runs photosite by photosite only");
        var sensor = SensorPresets.Get(name);
        if (fixedPattern) sensor = sensor with { PrnuPercent = 1.5, DsnuVolts = 2e-3, BlackLevel = 64 };
        var cube = Cube();
        var light = TabulatedSpectrum.Constant(1);
        var lanes = SensorSimulation.Run(sensor, cube, light, new SimulationOptions { Seed = 11, Threads = 2 });
        var scalar = SensorSimulation.Run(sensor, cube, light, new SimulationOptions { Seed = 11, Threads = 1, ScalarOnly = true });
        Assert.Equal(scalar.Dn, lanes.Dn);
        // The frame spans the regimes: dark photosites (μ < 10, inversion) and bright ones near the full well (PTRS).
        double k = sensor.SystemGain, black = sensor.BlackLevel;
        Assert.Contains(scalar.Dn, d => (d - black) / k < 10);
        Assert.Contains(scalar.Dn, d => (d - black) / k > 0.5 * sensor.FullWellElectrons);
    }

    /// <summary>
    /// Noise off, a fixed exposure: each raw value is min(Σ_b w_c,b·L_b·t, full well)·K + black, summed here in double
    /// from the channel weights — for a mosaic (one channel per photosite), full and wheel sensors with no more channels
    /// than SIMD lanes (all channels at once) and a full sensor with more (one dot product per channel).
    /// </summary>
    [Theory]
    [InlineData("nikon-d5100", false)]
    [InlineData("mosaic-16", false)]
    [InlineData("wheel-6", false)]
    [InlineData("cie-xyz", false)]
    [InlineData("mosaic-16", true)]
    public void NoiseOff_RawIsTheWeightedBandSum(string name, bool allChannelsAtEveryPixel)
    {
        // the weighted sum per pixel, no lens blur
        var sensor = SensorPresets.Get(name) with { OffAxis = OffAxisModel.None, Psf = PsfModel.None };
        if (allChannelsAtEveryPixel) sensor = sensor with { Arrangement = Arrangement.Full, Pattern = null, PatternName = null };
        var cube = Cube();
        var light = TabulatedSpectrum.Constant(1);
        var probe = SensorSimulation.Run(sensor, cube, light, new SimulationOptions { Noise = false });
        double t = 0.5 * probe.ExposureSeconds.Min();   // below saturation everywhere: the sum is not clipped
        sensor = sensor with { ExposureSeconds = t };
        var raw = SensorSimulation.Run(sensor, cube, light, new SimulationOptions { Noise = false, Threads = 2 });
        var w = raw.Weights;
        int n = cube.Bands, planes = sensor.Planes;
        double worst = 0;
        for (int y = 0; y < cube.Height; y++)
            for (int x = 0; x < cube.Width; x++)
                for (int k = 0; k < planes; k++)
                {
                    int c = sensor.Arrangement == Arrangement.Mosaic
                        ? sensor.Pattern![y % sensor.Pattern.GetLength(0), x % sensor.Pattern.GetLength(1)]
                        : k;
                    double sum = 0;
                    for (int b = 0; b < n; b++) sum += w[c, b] * cube.Data[(y * cube.Width + x) * n + b];
                    double expected = Math.Min(sum * t, sensor.FullWellElectrons) * sensor.SystemGain + sensor.BlackLevel;
                    double got = raw[x, y, k];
                    worst = Math.Max(worst, Math.Abs(got - expected) / Math.Max(expected, 1e-3));
                }
        output.WriteLine($"{name}{(allChannelsAtEveryPixel ? " (full)" : "")}: worst relative difference {worst:G3}");
        Assert.True(worst < 1e-5, $"{worst}");
    }
}
