using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Analysis;

/// <summary>
/// A render's output folder read back from disk: the spectral cube, the object-id image and what
/// render.json records (band grid, eq. 3 weights, reference white, object names and reflectances).
/// </summary>
public sealed class RenderFolder
{
    public required string Path { get; init; }
    public required SpectralImage Image { get; init; }
    public required int[] ObjectIds { get; init; }
    public required string[] ObjectNames { get; init; }
    public required string?[] ObjectReflectances { get; init; }
    public required double[] Wx { get; init; }
    public required double[] Wy { get; init; }
    public required double[] Wz { get; init; }
    public required Xyz White { get; init; }
    public required TabulatedSpectrum ReferenceWhite { get; init; }
    public required int ObserverDegrees { get; init; }
    public required string Integration { get; init; }
    public required JsonObject Json { get; init; }

    public static RenderFolder Open(string dir)
    {
        if (!Directory.Exists(dir)) throw new InputException(dir, "no such render folder", "give the -o folder of a 'spectral render' run");
        var jsonPath = System.IO.Path.Combine(dir, "render.json");
        if (!File.Exists(jsonPath)) throw new InputException(dir, "has no render.json", "give the -o folder of a 'spectral render' run");
        JsonObject json;
        try { json = JsonNode.Parse(File.ReadAllText(jsonPath)) as JsonObject ?? throw new InputException(jsonPath, "is not a JSON object"); }
        catch (JsonException e) { throw new InputException($"{jsonPath}:{(e.LineNumber ?? 0) + 1}", $"broken JSON: {e.Message}"); }
        try
        {
            var grid = BandGrid.Parse((string)json["bands"]!["grid"]!, $"{jsonPath}: $.bands.grid");
            var colour = json["colour"]!.AsObject();
            double[] Arr(JsonNode? n) => n!.AsArray().Select(v => (double)v!).ToArray();
            var spd = colour["reference_white_spd"]!;
            var white = new TabulatedSpectrum((string?)colour["reference_white"] ?? "white", Arr(spd["wavelengths_nm"]), Arr(spd["values"]), Extrapolation.Clamp);
            var w = Arr(colour["white_xyz"]);
            var objects = json["objects"]!.AsArray();
            var image = SpectralFiles.Read(dir, grid);
            int width = (int)json["width"]!, height = (int)json["height"]!;
            if (image.Width != width || image.Height != height || image.Bands != grid.Count)
                throw new InputException(dir, $"its spectral cube is {image.Width}×{image.Height}×{image.Bands} but render.json describes {width}×{height}×{grid.Count}",
                    "the folder mixes two renders; render again into an empty folder");
            int[] ids = ReadIds(dir, image);
            return new RenderFolder
            {
                Path = dir,
                Image = image,
                ObjectIds = ids,
                ObjectNames = objects.Select(o => (string)o!["name"]!).ToArray(),
                ObjectReflectances = objects.Select(o => (string?)o!["reflectance"]).ToArray(),
                Wx = Arr(colour["weights_x"]), Wy = Arr(colour["weights_y"]), Wz = Arr(colour["weights_z"]),
                White = new Xyz(w[0], w[1], w[2]),
                ReferenceWhite = white,
                ObserverDegrees = (int)colour["observer"]!,
                Integration = (string)colour["integration"]!,
                Json = json,
            };
        }
        catch (Exception e) when (e is NullReferenceException or InvalidOperationException or FormatException)
        {
            throw new InputException(jsonPath, $"is missing a field this tool writes ({e.Message})", "re-render the scene with this version");
        }
    }

    static int[] ReadIds(string dir, SpectralImage image)
    {
        var path = System.IO.Path.Combine(dir, "object-id.png");
        if (!File.Exists(path)) throw new InputException(dir, "has no object-id.png", "render with --formats including aov");
        var png = PngReader.Read(path);
        if (png.Width != image.Width || png.Height != image.Height) throw new InputException(path, $"is {png.Width}×{png.Height} but the cube is {image.Width}×{image.Height}");
        var ids = new int[png.Width * png.Height];
        for (int i = 0; i < ids.Length; i++) ids[i] = png.Samples[i * png.Channels] - 1;
        return ids;
    }

    public int ObjectIndex(string name) => Array.IndexOf(ObjectNames, name);

    /// <summary>Eq. 3 with the render's own weights.</summary>
    public Xyz ToXyz(ReadOnlySpan<double> bands)
    {
        double x = 0, y = 0, z = 0;
        for (int b = 0; b < Wx.Length; b++) { x += Wx[b] * bands[b]; y += Wy[b] * bands[b]; z += Wz[b] * bands[b]; }
        return new Xyz(x, y, z);
    }

    /// <summary>The mean spectrum of all pixels showing object <paramref name="index"/>, and their count.</summary>
    public (double[] Mean, int Pixels) MeanSpectrum(int index)
    {
        var sum = new double[Image.Bands];
        int count = 0;
        for (int i = 0; i < ObjectIds.Length; i++)
        {
            if (ObjectIds[i] != index) continue;
            var px = Image.Data.AsSpan(i * Image.Bands, Image.Bands);
            for (int b = 0; b < sum.Length; b++) sum[b] += px[b];
            count++;
        }
        if (count > 0) for (int b = 0; b < sum.Length; b++) sum[b] /= count;
        return (sum, count);
    }
}
