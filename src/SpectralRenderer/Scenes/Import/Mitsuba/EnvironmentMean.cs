using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Scenes.Import.Mitsuba;

/// <summary>The mean linear RGB of a lat-long (equirectangular) environment map, each row weighted by its solid angle.</summary>
public static class EnvironmentMean
{
    /// <summary>
    /// Mean R, G, B over the sphere: Σ_j sin θ_j Σ_i c_ij / (W·Σ_j sin θ_j), θ_j = π(j + ½)/H the polar angle of row j (the
    /// equal-angle rows of a lat-long map cover 2π sin θ_j·(π/H) sr each). OpenEXR only (scanline; none, ZIPS or ZIP).
    /// </summary>
    public static double[] Of(string path, string where)
    {
        if (!path.EndsWith(".exr", StringComparison.OrdinalIgnoreCase))
            throw new InputException(where, $"environment map {MessageText.Quote(Path.GetFileName(path))} is not OpenEXR",
                "convert it to a scanline OpenEXR (e.g. oiiotool sky.hdr --compression zip -o sky.exr)");
        var (width, height, channels, planes, _, _, _, _) = ExrReader.ReadChannels(InputFile.ReadAllBytes(path, "environment map"), path);
        float[] Plane(string name)
        {
            int i = channels.FindIndex(c => c.Name == name);
            return i >= 0
                ? planes[i]
                : throw new InputException(path, $"no '{name}' channel", "an RGB environment map has R, G and B channels");
        }
        var r = Plane("R");
        var g = Plane("G");
        var b = Plane("B");
        double sr = 0, sg = 0, sb = 0, weight = 0;
        for (int j = 0; j < height; j++)
        {
            double w = Math.Sin(Math.PI * (j + 0.5) / height);
            double rr = 0, gg = 0, bb = 0;
            for (int i = j * width; i < (j + 1) * width; i++)
            {
                if (!(float.IsFinite(r[i]) && float.IsFinite(g[i]) && float.IsFinite(b[i])))
                    throw new InputException(path, $"pixel ({i - j * width}, {j}) is not finite", "fix the image's NaN or infinite pixels");
                rr += Math.Max(0, r[i]); gg += Math.Max(0, g[i]); bb += Math.Max(0, b[i]);
            }
            sr += w * rr; sg += w * gg; sb += w * bb;
            weight += w * width;
        }
        return [sr / weight, sg / weight, sb / weight];
    }
}
