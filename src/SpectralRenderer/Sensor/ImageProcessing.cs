using SpectralRenderer.Color;

namespace SpectralRenderer.Sensor;

/// <summary>
/// The processed image: per pixel and channel the estimated photo-electron rate ė = (DN − black)/(K·t) (e⁻/s,
/// after demosaicking a mosaic), the white-balanced signal s = ė/ė_white, its XYZ through the colour-correction
/// matrix, and 8-bit sRGB (both empty when the display stage was not asked for).
/// </summary>
public sealed record ProcessedImage(int Width, int Height, int Channels, float[] Rates, float[] Balanced, Xyz[] Xyz, byte[] Srgb8,
    DemosaicMethod? Demosaicked);

public static class ImageProcessing
{
    /// <param name="display">Whether to compute the colour-corrected XYZ and sRGB of every pixel (false: only the rates and the balanced
    /// signals, for recovery).</param>
    public static ProcessedImage Run(RawFrame raw, ColourCorrection colour, DemosaicMethod method = DemosaicMethod.Malvar,
        bool display = true)
    {
        var sensor = raw.Sensor;
        int w = raw.Width, h = raw.Height, cc = sensor.ChannelCount, pixels = w * h;
        double k = sensor.SystemGain;
        float[] rates;
        DemosaicMethod? used = null;
        if (sensor.Arrangement == Arrangement.Mosaic)
        {
            // Balance the sites first, so the demosaicker interpolates comparable values, then scale back to e⁻/s.
            var site = new float[pixels];
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                {
                    int c = sensor.ChannelAt(x, y), i = y * w + x;
                    site[i] = (float)((raw.Dn[i] - sensor.BlackLevel) / (k * raw.ExposureOf(c)) / colour.WhiteRate[c]);
                }
            used = method == DemosaicMethod.Malvar && !sensor.IsBayer ? DemosaicMethod.Bilinear : method;
            var balanced = Demosaic.Run(sensor, site, w, h, used.Value);
            rates = new float[balanced.Length];
            for (int i = 0; i < pixels; i++)
                for (int c = 0; c < cc; c++)
                    rates[i * cc + c] = (float)(balanced[i * cc + c] * colour.WhiteRate[c]);
            return Finish(w, h, cc, rates, balanced, colour, used, display);
        }
        rates = new float[pixels * cc];
        var bal = new float[pixels * cc];
        for (int i = 0; i < pixels; i++)
            for (int c = 0; c < cc; c++)
            {
                double r = (raw.Dn[i * cc + c] - sensor.BlackLevel) / (k * raw.ExposureOf(c));
                rates[i * cc + c] = (float)r;
                bal[i * cc + c] = (float)(r / colour.WhiteRate[c]);
            }
        return Finish(w, h, cc, rates, bal, colour, used, display);
    }

    static ProcessedImage Finish(int w, int h, int cc, float[] rates, float[] balanced, ColourCorrection colour, DemosaicMethod? used,
        bool display)
    {
        if (!display) return new ProcessedImage(w, h, cc, rates, balanced, [], [], used);
        int pixels = w * h;
        var xyz = new Xyz[pixels];
        var rgb = new byte[pixels * 3];
        Parallel.For(0, h, y =>
        {
            Span<double> s = stackalloc double[cc];
            for (int i = y * w; i < (y + 1) * w; i++)
            {
                for (int c = 0; c < cc; c++) s[c] = balanced[i * cc + c];
                xyz[i] = colour.ToXyz(s);
                // A monochrome sensor records no colour: its image is grey, R = G = B = the sRGB code of Y (issue 24), so
                // neither the light's chromaticity nor the 8-bit rounding of three channels can tint it.
                var (r, g, b) = cc == 1 ? Grey(RgbSpace.Srgb.Encode8(xyz[i].Y)) : RgbSpace.Srgb.Encode8(xyz[i]);
                rgb[3 * i] = r; rgb[3 * i + 1] = g; rgb[3 * i + 2] = b;
            }
        });
        return new ProcessedImage(w, h, cc, rates, balanced, xyz, rgb, used);
    }

    static (byte, byte, byte) Grey(byte v) => (v, v, v);
}
