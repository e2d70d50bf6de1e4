using System.Runtime.CompilerServices;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Output;

/// <summary>
/// The auxiliary images for analysis (§3.4): per light, where it reaches the surface seen
/// (mask-lit-K.png); where the specular term exceeds a fraction of the diffuse (mask-highlight.png);
/// and the ground-truth diffuse reflectance of what each pixel sees (reflectance.exr with T.λ channels,
/// lossless and compact: the truth is constant over each object).
/// </summary>
public static class AnalysisImages
{
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static void Write(Scene scene, RenderResult result, string outDir, Action<string> done, ReusedFiles? reuse = null)
    {
        var image = result.Image;
        int n = image.Width * image.Height;
        var mask = new byte[n];
        for (int k = 0; k < LitMaskCount(scene); k++)
        {
            var name = $"mask-lit-{k}.png";
            if (reuse?.Copy(name, outDir) != true)
            {
                LitMask(result, k, mask);
                AtomicFile.Write(Path.Combine(outDir, name), s => PngWriter.WriteGray8(s, image.Width, image.Height, mask));
            }
            done(name);
        }
        AtomicFile.Write(Path.Combine(outDir, "mask-highlight.png"),
            s => PngWriter.WriteGray8(s, image.Width, image.Height, result.Highlights));
        done("mask-highlight.png");

        if (reuse?.Copy("reflectance.exr", outDir) != true)
            ExrWriter.Write(Path.Combine(outDir, "reflectance.exr"), image.Width, image.Height, image.Grid, GroundTruthBands(scene, result),
                null, ReflectanceOptions(scene, result.Crop));
        done("reflectance.exr");
    }

    /// <summary>Lit masks of a render (mask-lit-K.png for K below it): a light each, up to <see cref="LitMasks.MaxLights"/>.</summary>
    public static int LitMaskCount(Scene scene) => Math.Min(LitMasks.MaxLights, scene.Lights.Count);

    /// <summary>mask-lit-<paramref name="k"/>.png's pixels: 255 where light k reaches the surface the centre ray sees, else 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static void LitMask(RenderResult result, int k, Span<byte> mask)
    {
        for (int i = 0; i < mask.Length; i++) mask[i] = result.LitMasks.IsLit(i, k) ? (byte)255 : (byte)0;
    }

    /// <summary>reflectance.exr's options: T.λ channels, no colour channels, the crop as its data window in the film.</summary>
    public static ExrOptions ReflectanceOptions(Scene scene, PixelRect crop) => new()
    {
        Reflective = true,
        Rgb = false,
        Colorimeter = scene.Colorimeter,
        DataX = crop.X0,
        DataY = crop.Y0,
        DisplayWidth = scene.Camera.Width,
        DisplayHeight = scene.Camera.Height
    };

    /// <summary>The bytes reflectance.exr of this scene starts with (magic, version, header): what the writer's settings alone
    /// decide.</summary>
    public static byte[] ReflectanceFileStart(Scene scene, PixelRect crop) =>
        ExrWriter.FileStart(crop.Width, crop.Height, scene.Grid, ReflectanceOptions(scene, crop));

    /// <summary>The ground-truth diffuse reflectance of what each pixel sees (reflectance.exr), as band-sequential planes
    /// (<see cref="SpectralImage.CopyBands"/>), built directly.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static float[] GroundTruthBands(Scene scene, RenderResult result)
    {
        var ids = result.ObjectIds;
        int n = ids.Length, bands = result.Image.Bands;
        var planes = new float[n * bands];
        var value = new float[scene.Objects.Count + 1];  // per band: index id + 1, 0 for background (id −1)
        for (int b = 0; b < bands; b++)
        {
            for (int o = 0; o < scene.Objects.Count; o++) value[o + 1] = scene.Materials[scene.Objects[o].Material].Diffuse[b];
            var plane = planes.AsSpan(b * n, n);
            for (int i = 0; i < plane.Length; i++) plane[i] = value[ids[i] + 1];
        }
        return planes;
    }
}
