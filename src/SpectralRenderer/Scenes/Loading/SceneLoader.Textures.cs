using System.Globalization;
using System.Numerics;
using System.Text.Json;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Scenes.Textures;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// Textures (issue 26): a material's "diffuse" or "specular", or its emission's "spectrum", given as { "texture": FILE, … }
// — an ENVI cube, a spectral OpenEXR (T.<λ>nm or S0.<λ>nm channels), a stack of single-band PNGs with their wavelengths,
// or an sRGB PNG uplifted to reflectance spectra. The spectrum it stands for is the texture's mean; the texels reach the
// material afterwards (AttachTextures, ParseEmission), so the material models read those keys as they always have.
public sealed partial class SceneLoader
{
    static readonly string[] TextureKeys = ["texture", "wavelengths", "scale", "uv_transform"];
    readonly Dictionary<string, TextureBinding> _pendingTextures = new(StringComparer.Ordinal);

    /// <summary>Is <paramref name="e"/> a texture object ({"texture": …})?</summary>
    static bool IsTexture(JsonElement e) => e.ValueKind == JsonValueKind.Object && TryGet(e, "texture", out _);

    /// <summary>A texture given where a spectrum is expected: read, checked as a reflectance (an emission's as a radiance), kept
    /// for its material; its mean returned.</summary>
    TabulatedSpectrum TextureSpectrum(JsonElement e, string path)
    {
        bool emission = path.EndsWith(".emission.spectrum", StringComparison.Ordinal);
        if (!emission && !path.EndsWith(".diffuse", StringComparison.Ordinal) && !path.EndsWith(".specular", StringComparison.Ordinal)
            && !path.EndsWith(".reflectance", StringComparison.Ordinal))
            throw Error(path,
                "only a material's \"diffuse\", \"specular\", a lambertian's \"reflectance\" or emission "
                    + "\"spectrum\" can be a texture so far",
                "give a spectrum here, and the texture as a material's \"diffuse\", \"specular\" or \"emission\": { \"spectrum\": … }");
        Keys(e, path, TextureKeys);
        var uv = TryGet(e, "uv_transform", out var u) ? UvTransformOf(u, $"{path}.uv_transform") : UvTransform.Identity;
        var texture = ReadTexture(e, path);
        double scale = Number(e, "scale", path, 1, 0, 1e6);
        texture.Scale(scale);
        var (min, max, mean) = texture.Summary();
        var inv = CultureInfo.InvariantCulture;
        if (!float.IsFinite(min) || !float.IsFinite(max))
            throw Error($"{path}.texture", $"texture {texture.Source} holds values that are not finite numbers",
                "write the texture again with finite reflectances");
        if (max >= 2 && !emission)
            throw Error($"{path}.texture",
                $"texture {texture.Source} reaches {max.ToString("0.###", inv)}: a reflectance cannot exceed 1 (this looks like percent)",
                "add \"scale\": 0.01 to the texture object");
        if (min < -1e-6)
            throw Error($"{path}.texture",
                $"texture {texture.Source} goes down to {min.ToString("G4", inv)}: "
                    + $"{(emission ? "a radiance" : "a reflectance")} cannot be negative",
                "clip the texture's noise below zero to 0");
        if (max > 1 && !emission)
            _warnings.Add($"{Where(path)}: warning: texture {texture.Source} reaches {max.ToString("0.###", inv)} > 1; rendered as given");
        _pendingTextures[path] = new TextureBinding(texture, uv);
        return mean;
    }

    /// <summary>The textures read for <paramref name="materialPath"/>'s "diffuse" (a lambertian's "reflectance") and "specular"
    /// go onto the material made from them.</summary>
    void AttachTextures(Material material, string materialPath)
    {
        // A lambertian's "reflectance" is its diffuse lobe (m_diff = m_amb = ρ).
        if (_pendingTextures.Remove($"{materialPath}.diffuse", out var binding)
            || _pendingTextures.Remove($"{materialPath}.reflectance", out binding))
            material.DiffuseTexture = binding;
        if (_pendingTextures.Remove($"{materialPath}.specular", out binding)) material.SpecularTexture = binding;
    }

    /// <summary>The texture read for an emission's "spectrum" at <paramref name="path"/>, its texels scaled by the emission's k, or
    /// null.</summary>
    TextureBinding? EmissionTexture(string path, double k)
    {
        if (!_pendingTextures.Remove($"{path}.spectrum", out var binding)) return null;
        binding.Texture.Scale(k);
        return binding;
    }

    SpectralTexture ReadTexture(JsonElement e, string path)
    {
        var t = Required(e, "texture", path);
        if (t.ValueKind == JsonValueKind.Array) return PngStack(t, e, path);
        var file = String(t, $"{path}.texture");
        if (file.Contains("{nm}", StringComparison.Ordinal)) return PngStack(t, e, path);
        if (TryGet(e, "wavelengths", out _))
            throw Error($"{path}.wavelengths", "\"wavelengths\" belongs to a stack of PNG bands",
                "name the bands as a list of files or a pattern with {nm}, or drop \"wavelengths\"");
        if (file.StartsWith("data:", StringComparison.OrdinalIgnoreCase)) return DataTexture(file, path);
        var full = TextureFile(file, $"{path}.texture");
        var ext = Path.GetExtension(full).ToLowerInvariant();
        try
        {
            if (ext == ".exr")
            {
                var exr = ExrReader.Read(full);
                return FromImage(exr.Image, full);
            }
            if (ext == ".png") return RgbTexture(full, path);
            if (ext is ".jpg" or ".jpeg") return JpegTexture(full);
            var cube = EnviReader.Open(EnviImage(full, path));
            return new SpectralTexture(full, cube.Width, cube.Height, Centres(cube.Grid), new EnviRows(cube));
        }
        catch (InputException ex) when (!ex.Where.StartsWith(_file, StringComparison.Ordinal))
        {
            throw Error($"{path}.texture", $"{ex.Where}: {ex.What}", ex.Hint);
        }
    }

    /// <summary>An ENVI cube named by its header or its image: the image path (beside the .hdr, with a usual extension or none).</summary>
    string EnviImage(string full, string path)
    {
        if (!full.EndsWith(".hdr", StringComparison.OrdinalIgnoreCase)) return full;
        var stem = full[..^4];
        foreach (var ext in new[] { ".img", ".raw", ".bsq", ".bil", ".bip", ".dat", "" })
            if (File.Exists(stem + ext)) return stem + ext;
        throw Error($"{path}.texture", $"ENVI header {full} has no image beside it",
            $"expected {Path.GetFileName(stem)}.img (or .raw, .bsq, .dat)");
    }

    string TextureFile(string file, string path)
    {
        var full = Path.GetFullPath(Path.Combine(_dir, file));
        if (!File.Exists(full))
            throw Error(path, $"texture file '{file}' not found (looked in {_dir})", "give the path relative to the scene file");
        return full;
    }

    /// <summary>A spectral image's pixels as texels, each tabulated at its band centres.</summary>
    static SpectralTexture FromImage(SpectralImage image, string source) =>
        new(source, image.Width, image.Height, Centres(image.Grid), image.Data);

    static double[] Centres(BandGrid grid)
    {
        var wavelengths = new double[grid.Count];
        for (int b = 0; b < wavelengths.Length; b++) wavelengths[b] = grid.Centre(b);
        return wavelengths;
    }

    /// <summary>Single-band PNGs (8 or 16 bit, grey, linear: value / (2^bits − 1)), one per wavelength of "wavelengths":
    /// a list of files, or one pattern whose "{nm}" is each wavelength.</summary>
    SpectralTexture PngStack(JsonElement t, JsonElement e, string path)
    {
        var wl = Required(e, "wavelengths", path);
        if (wl.ValueKind != JsonValueKind.Array || wl.GetArrayLength() < 2)
            throw Error($"{path}.wavelengths", "expected a list of at least two wavelengths in nm, one per PNG band",
                "e.g. \"wavelengths\": [400, 410, 420]");
        var wavelengths = new double[wl.GetArrayLength()];
        for (int i = 0; i < wavelengths.Length; i++)
        {
            wavelengths[i] = Number(wl[i], $"{path}.wavelengths[{i}]", 100, 5000);
            if (i > 0 && !(wavelengths[i] > wavelengths[i - 1]))
                throw Error($"{path}.wavelengths[{i}]", "wavelengths must be strictly ascending",
                    "list the bands from short to long wavelengths");
        }
        var files = new string[wavelengths.Length];
        if (t.ValueKind == JsonValueKind.Array)
        {
            if (t.GetArrayLength() != wavelengths.Length)
                throw Error($"{path}.texture", $"{t.GetArrayLength()} PNG files for {wavelengths.Length} wavelengths",
                    "give one file per wavelength");
            for (int i = 0; i < files.Length; i++) files[i] = TextureFile(String(t[i], $"{path}.texture[{i}]"), $"{path}.texture[{i}]");
        }
        else
        {
            var pattern = String(t, $"{path}.texture");
            for (int i = 0; i < files.Length; i++)
                files[i] = TextureFile(
                    pattern.Replace("{nm}", wavelengths[i].ToString("0.###", CultureInfo.InvariantCulture), StringComparison.Ordinal),
                    $"{path}.texture");
        }
        // One band file at a time, each kept as its samples (2 bytes each, not a float cube); texels are made from them a block
        // of rows at a time (PngStackRows).
        var planes = new ushort[wavelengths.Length][];
        var max = new float[planes.Length];
        int width = 0, height = 0;
        for (int b = 0; b < planes.Length; b++)
        {
            PngImage png;
            try { png = PngReader.Read(files[b]); }
            catch (InputException ex) { throw Error($"{path}.texture", $"{ex.Where}: {ex.What}", ex.Hint); }
            if (png.Channels != 1)
                throw Error($"{path}.texture", $"{files[b]} has {png.Channels} channels: a band of a PNG stack is one grey channel",
                    "write each band as a greyscale PNG");
            if (b == 0) { width = png.Width; height = png.Height; }
            else if (png.Width != width || png.Height != height)
                throw Error($"{path}.texture", $"{files[b]} is {png.Width}×{png.Height}, the first band {width}×{height}",
                    "every band of a stack has the same size");
            planes[b] = png.Samples;
            max[b] = (1 << png.BitDepth) - 1;
        }
        return new SpectralTexture(files[0], width, height, wavelengths, new PngStackRows(planes, max, width));
    }

    static readonly Lazy<SigmoidUplift> Uplift = new(() => new SigmoidUplift());

    /// <summary>An sRGB PNG or JPEG given inline as a base64 data: URI (RFC 2397; an imported glTF's embedded image), e.g.
    /// "data:image/png;base64,iVBORw0…": uplifted as the file would be.</summary>
    SpectralTexture DataTexture(string uri, string path)
    {
        int comma = uri.IndexOf(',', StringComparison.Ordinal);
        var header = comma < 0 ? uri : uri[..comma];
        if (comma < 0 || !header.EndsWith(";base64", StringComparison.OrdinalIgnoreCase))
            throw Error($"{path}.texture", "a data: URI texture must be base64", "data:image/png;base64,… or data:image/jpeg;base64,…");
        byte[] bytes;
        try { bytes = Convert.FromBase64String(uri[(comma + 1)..]); }
        catch (FormatException) { throw Error($"{path}.texture", "the data: URI is not valid base64", "encode the image again"); }
        var source = $"{header},…";
        try
        {
            if (JpegReader.IsJpeg(bytes)) return JpegTexture(JpegReader.Read(bytes, source), source);
            var png = PngReader.Read(new MemoryStream(bytes), source);
            return RgbTexture(png, source, path);
        }
        catch (InputException ex) when (!ex.Where.StartsWith(_file, StringComparison.Ordinal))
        {
            throw Error($"{path}.texture", $"{ex.Where}: {ex.What}", ex.Hint);
        }
    }

    /// <summary>An sRGB PNG (RGB, palette or grey as R = G = B, any bit depth; alpha not used), each colour uplifted to a
    /// reflectance spectrum (<see cref="SigmoidUplift"/>).</summary>
    SpectralTexture RgbTexture(string full, string path) => RgbTexture(PngReader.Read(full), full, path);

    SpectralTexture RgbTexture(PngImage png, string full, string path)
    {
        var samples = png.Samples;
        return png.Channels == 3
            ? Uplifted(full, png.Width, png.Height, (1 << png.BitDepth) - 1, i => (samples[3 * i], samples[3 * i + 1], samples[3 * i + 2]))
            : Uplifted(full, png.Width, png.Height, (1 << png.BitDepth) - 1, i => (samples[i], samples[i], samples[i]));
    }

    /// <summary>A baseline JPEG (<see cref="JpegReader"/>), its colours sRGB as a PNG's are; a greyscale JPEG is R = G = B.</summary>
    static SpectralTexture JpegTexture(string full) => JpegTexture(JpegReader.Read(full), full);

    static SpectralTexture JpegTexture(JpegImage jpeg, string full)
    {
        var s = jpeg.Samples;
        return jpeg.Channels == 3
            ? Uplifted(full, jpeg.Width, jpeg.Height, 255, i => (s[3 * i], s[3 * i + 1], s[3 * i + 2]))
            : Uplifted(full, jpeg.Width, jpeg.Height, 255, i => (s[i], s[i], s[i]));
    }

    /// <summary>Texels from sRGB codes (0 … <paramref name="max"/>), each uplifted to a reflectance spectrum.</summary>
    static SpectralTexture Uplifted(string source, int width, int height, int max, Func<int, (int R, int G, int B)> texel)
    {
        var uplift = Uplift.Value;
        int n = SigmoidUplift.Wavelengths.Length;
        var values = new float[(long)width * height * n];
        Parallel.For(0, height, y =>
        {
            for (int i = y * width; i < (y + 1) * width; i++)
            {
                var (r, g, b) = texel(i);
                var spectrum = uplift.FromSrgbCodes(r, g, b, max);
                for (int j = 0; j < n; j++) values[(long)i * n + j] = (float)spectrum[j];
            }
        });
        return new SpectralTexture(source, width, height, SigmoidUplift.Wavelengths, values);
    }

    /// <summary>"uv_transform": {"scale": s | [su, sv], "offset": [ou, ov], "rotation": degrees, "wrap": "repeat" | "clamp" |
    /// "mirror"}.</summary>
    UvTransform UvTransformOf(JsonElement e, string path)
    {
        Object(e, path);
        Keys(e, path, "scale", "offset", "rotation", "wrap");
        var scale = Vector2.One;
        if (TryGet(e, "scale", out var s))
            scale =
                s.ValueKind == JsonValueKind.Number ? new Vector2((float)Number(s, $"{path}.scale", -1e6, 1e6)) : Pair(s, $"{path}.scale");
        if (scale.X == 0 || scale.Y == 0)
            throw Error($"{path}.scale", "a zero scale squeezes the texture to a line", "use a non-zero scale, e.g. 2 to repeat it twice");
        var offset = TryGet(e, "offset", out var o) ? Pair(o, $"{path}.offset") : Vector2.Zero;
        float rotation = (float)Number(e, "rotation", path, 0, -3600, 3600);
        var wrap = TextureWrap.Repeat;
        if (TryGet(e, "wrap", out var w))
        {
            var name = String(w, $"{path}.wrap").ToLowerInvariant();
            string[] names = ["repeat", "clamp", "mirror"];
            wrap = name switch
            {
                "repeat" => TextureWrap.Repeat,
                "clamp" => TextureWrap.Clamp,
                "mirror" => TextureWrap.Mirror,
                _ => throw Error($"{path}.wrap", $"unknown wrap '{name}'",
                    InputException.DidYouMean(name, names) ?? "use repeat, clamp or mirror"),
            };
        }
        return new UvTransform(scale, offset, rotation, wrap);
    }

    Vector2 Pair(JsonElement e, string path)
    {
        if (e.ValueKind != JsonValueKind.Array || e.GetArrayLength() != 2)
            throw Error(path, $"expected [u, v], found {Kind(e)}", "e.g. [2, 1]");
        return new Vector2((float)Number(e[0], $"{path}[0]", -1e6, 1e6), (float)Number(e[1], $"{path}[1]", -1e6, 1e6));
    }
}

/// <summary>An ENVI cube's texels, read from its file a block of rows at a time (<see cref="EnviCube.ReadRows"/>).</summary>
sealed class EnviRows(EnviCube cube) : TexelRows
{
    public override void Read(int y0, int rows, Span<float> dst) => cube.ReadRows(y0, rows, dst);
}

/// <summary>A PNG stack's texels from its band planes (sample / (2^bits − 1), linear), a block of rows at a time.</summary>
sealed class PngStackRows(ushort[][] planes, float[] max, int width) : TexelRows
{
    public override void Read(int y0, int rows, Span<float> dst)
    {
        int n = planes.Length, first = y0 * width;
        for (int b = 0; b < n; b++)
        {
            var plane = planes[b];
            float m = max[b];
            for (int i = 0; i < rows * width; i++) dst[i * n + b] = plane[first + i] / m;
        }
    }
}
