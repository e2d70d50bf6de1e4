using SpectralRenderer.Sensor;

namespace SpectralRenderer.Tests.Sensor;

/// <summary>Demosaicking against analytic images: per-channel planes that are constant or linear in x and y are reproduced exactly in the
/// interior.</summary>
public class DemosaicTests
{
    static float Plane(int c, int x, int y) => 10 + 3 * c + (0.5f + 0.1f * c) * x + (0.25f - 0.05f * c) * y;

    [Theory]
    [InlineData("nikon-d5100", DemosaicMethod.Bilinear, 1)]
    [InlineData("nikon-d5100", DemosaicMethod.Malvar, 2)]
    [InlineData("mosaic-16", DemosaicMethod.Bilinear, 3)]
    public void LinearPlanes_AreReproducedExactly(string preset, DemosaicMethod method, int margin)
    {
        var sensor = SensorPresets.Get(preset);
        const int w = 24, h = 20;
        var mosaic = new float[w * h];
        for (int y = 0; y < h; y++) for (int x = 0; x < w; x++) mosaic[y * w + x] = Plane(sensor.ChannelAt(x, y), x, y);
        var full = Demosaic.Run(sensor, mosaic, w, h, method);
        int cc = sensor.ChannelCount;
        for (int y = margin; y < h - margin; y++)
            for (int x = margin; x < w - margin; x++)
                for (int c = 0; c < cc; c++)
                    Assert.Equal(Plane(c, x, y), full[(y * w + x) * cc + c], 3);
    }

    [Fact]
    public void Malvar_UsesTheGradientOfTheMeasuredChannel()
    {
        // Green is a quadratic bump, red and blue flat: bilinear leaves green's curvature error at red sites, Malvar's
        // correction from the red Laplacian (zero here) does not add one, and both keep measured values.
        var sensor = SensorPresets.Get("nikon-d5100");
        const int w = 16, h = 16;
        var mosaic = new float[w * h];
        for (int y = 0; y < h; y++) for (int x = 0; x < w; x++) mosaic[y * w + x] = sensor.ChannelAt(x, y) == 1 ? (x - 8) * (x - 8) : 5;
        var m = Demosaic.Run(sensor, mosaic, w, h, DemosaicMethod.Malvar);
        for (int y = 2; y < h - 2; y++)
            for (int x = 2; x < w - 2; x++)
                if (sensor.ChannelAt(x, y) == 1) Assert.Equal(mosaic[y * w + x], m[(y * w + x) * 3 + 1]);
                else Assert.Equal(5, m[(y * w + x) * 3 + sensor.ChannelAt(x, y)]);
    }
}

/// <summary>The small dense solver and eigen-decomposition against their defining identities.</summary>
public class DenseTests
{
    [Fact]
    public void SymmetricEigen_ReconstructsTheMatrix_WithOrthonormalVectors()
    {
        int n = 7;
        var s = new double[n, n];
        for (int i = 0; i < n; i++) for (int j = 0; j <= i; j++) s[i, j] = s[j, i] = Math.Sin(i * 3 + j) + (i == j ? 4 : 0);
        var (values, v) = Dense.SymmetricEigen(s);
        for (int k = 1; k < n; k++) Assert.True(values[k] <= values[k - 1]);
        var vt = Dense.Transpose(v);
        var back = Dense.Multiply(Dense.Multiply(v, DiagonalOf(values)), vt);
        var id = Dense.Multiply(vt, v);
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++)
            {
                Assert.Equal(s[i, j], back[i, j], 10);
                Assert.Equal(i == j ? 1 : 0, id[i, j], 10);
            }
    }

    static double[,] DiagonalOf(double[] d)
    {
        var m = new double[d.Length, d.Length];
        for (int i = 0; i < d.Length; i++) m[i, i] = d[i];
        return m;
    }

    [Fact]
    public void Solve_NeedsPivoting_AndGivesTheSolution()
    {
        var a = new double[,] { { 0, 2, 1 }, { 1, 1, 1 }, { 2, 1, 0 } };
        var x = Dense.Solve(a, new double[,] { { 5 }, { 6 }, { 4 } });
        var ax = Dense.Multiply(a, x);
        Assert.Equal(5, ax[0, 0], 12); Assert.Equal(6, ax[1, 0], 12); Assert.Equal(4, ax[2, 0], 12);
        Assert.Throws<InvalidOperationException>(() => Dense.Solve(new double[,] { { 1, 2 }, { 2, 4 } }, new double[,] { { 1 }, { 2 } }));
    }
}
