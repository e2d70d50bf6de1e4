using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Two renders of one scene by two unbiased estimators (with and without a light tree, a portal, …): the per-pixel
/// differences of band 0, their mean and the standard error of that mean (the pixels as independent samples), and the
/// second image's mean level. The estimators agree when the mean difference is within 3 standard errors of 0.
/// </summary>
static class PairedImages
{
    public static (double Mean, double Sigma, double Level) Difference(SpectralImage a, SpectralImage b)
    {
        int pixels = a.Width * a.Height;
        double s1 = 0, s2 = 0, level = 0;
        for (int y = 0; y < a.Height; y++)
            for (int x = 0; x < a.Width; x++)
            {
                double d = a[x, y, 0] - b[x, y, 0];
                s1 += d;
                s2 += d * d;
                level += b[x, y, 0];
            }
        double mean = s1 / pixels;
        return (mean, Math.Sqrt((s2 / pixels - mean * mean) / (pixels - 1)), level / pixels);
    }
}
