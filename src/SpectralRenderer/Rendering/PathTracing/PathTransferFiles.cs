using System.Globalization;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.PathTracing;

/// <summary>
/// A path render's per-light transfer (<see cref="PathTransfer"/>) in <c>lights/</c>:
/// <list type="bullet">
/// <item><c>lights.json</c>: <c>"kind": "path"</c>, the layout, the film and band counts, the internal grid (its width in nm,
/// the sub-bands' edges), the lights (name, spectrum, band values) and the groups in file order (each light, then
/// "emitters and sky").</item>
/// <item><c>transfer.npy</c>: float32 [H, W, K + 1, F]: per pixel and light k its path weights T_k,f on the sub-band grid
/// (W·m⁻²·sr⁻¹·nm⁻¹ of radiance per unit of the light's spectrum × intensity), then the emitters' and the sky's radiance F_f
/// (W·m⁻²·sr⁻¹·nm⁻¹). The pixel's radiance on the grid is F_f + Σ_k T_k,f · E_k,f; an output band is the mean of its
/// sub-bands.</item>
/// <item><c>shift.npy</c> (version 2, a scene with a fluorescent material and scene lights): float32 [H, W, K, R, C]: per
/// pixel and light k the matrix B_k of its paths through a fluorescent shift, from excitation sub-band Column0 + c to
/// emission sub-band Row0 + r (lights.json "shift" gives both ranges); the radiance gains Σ_c B_k,r,c · E_k,Column0+c at
/// sub-band Row0 + r.</item>
/// <item><c>ids.npy</c>: float32 [H, W, 3]: the object index + 1 the centre ray hit (0 = background), then the lights that
/// reach its surface point (bit k = light k) as two 16-bit halves, low then high (each exact in a float32).</item>
/// </list>
/// Rows of a shard's strip are the whole film's rows, so shards merge by offset. <c>"version"</c> is 2 (this layout; 1 or
/// absent: the same without a shift, as written before fluorescent transfers, and still read).
/// </summary>
internal static class PathTransferFiles
{
    public const string Kind = "path";
    public const string TransferFile = "transfer.npy", IdsFile = "ids.npy", ShiftFile = "shift.npy";

    /// <summary>The layout written (1: before the fluorescent shift block; 2: with it when a scene has one).</summary>
    public const int Version = 2;

    const string Damaged = "lights/lights.json is not as a path render writes it: render the folder again with the lights output";

    /// <summary>The path transfer's format: kind "path", written by shards too (joined by rows), the sub-band film for the
    /// camera.</summary>
    public static readonly TransferFormat Format = new PathFormat();

    sealed class PathFormat : TransferFormat
    {
        public override string Kind => PathTransferFiles.Kind;
        public override string Integrator => "path";
        public override CameraRoute Route => CameraRoute.SubBandFilm;
        public override bool Shards => true;

        public override (string Option, string What, string Hint)? Refuses(Scene scene) => scene.TargetError > 0
            ? ("--target-error", "a path render's per-light transfer (lights) needs the same samples in every pixel: adaptive " +
                "sampling stops a pixel by its luminance, which follows the lights' spectra, so a relight could not equal a render",
                "leave out --target-error (fixed --spp), or leave lights out of the formats")
            : null;

        public override string? RefusesNewSpectrum(Light light) => light is GoniometricLight
            ? "is goniometric: its candela are radiance per lumen of its spectrum, so a new spectrum rescales its path weights, " +
                "which a path render's transfer holds"
            : null;

        /// <summary>(K + 1) × F floats per pixel, and K × R × C with a fluorescent shift.</summary>
        public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene) =>
            [("per-light transfer (path)", PathTransfer.Bytes(scene, (long)scene.Camera.Width * scene.Camera.Height))];

        public override ILightTransfer Read(string outDir, Scene scene) => PathTransferFiles.Read(outDir, scene);

        /// <summary>transfer.npy (K + 1, F), shift.npy (K, R, C), ids.npy (3) per pixel; K, F, R, C from the shard's lights.json.</summary>
        public override int[]? RowShape(string file, string lightsDir)
        {
            if (file is not (TransferFile or ShiftFile or IdsFile)) return null;
            if (file == IdsFile) return [3];
            var path = Path.Combine(lightsDir, "lights.json");
            var r = new JsonFields(path, "render the shard again with the lights output");
            var json = JsonFields.ParseFile(path, "lights.json", r.Hint);
            int lights = r.Array(json, "lights", "$").Count, sub = r.Int(json, "sub_bands", "$", 1, 1 << 20);
            if (file == TransferFile) return [lights + 1, sub];
            var shift = ReadShift(r, json, sub);
            if (shift.IsEmpty) throw r.Bad("$.shift", "is missing, but the shard wrote lights/shift.npy");
            return [lights, shift.Rows, shift.Columns];
        }
    }

    public static void Write(Scene scene, PathTransfer t, string outDir, Action<string> done)
    {
        var dir = Path.Combine(outDir, TransferFormat.Folder);
        Directory.CreateDirectory(dir);
        int h = t.Region.Height, w = t.Region.Width;
        AtomicFile.Write(Path.Combine(dir, TransferFile), s => NpyWriter.Write(s, [h, w, t.Lights + 1, t.SubBands], t.Data));
        done($"{TransferFormat.Folder}/{TransferFile}");
        if (!t.Shift.IsEmpty)
        {
            int[] shape = [h, w, t.Lights, t.Shift.Rows, t.Shift.Columns];
            AtomicFile.Write(Path.Combine(dir, ShiftFile), s => NpyWriter.Write(s, shape, t.Blocks));
            done($"{TransferFormat.Folder}/{ShiftFile}");
        }
        var ids = new float[3 * t.ObjectIds.Length];
        for (int i = 0; i < t.ObjectIds.Length; i++)
        {
            ids[3 * i] = t.ObjectIds[i] + 1;
            ids[3 * i + 1] = t.LitMasks[i] & 0xFFFF;
            ids[3 * i + 2] = t.LitMasks[i] >> 16;
        }
        AtomicFile.Write(Path.Combine(dir, IdsFile), s => NpyWriter.Write(s, [h, w, 3], ids));
        done($"{TransferFormat.Folder}/{IdsFile}");
        AtomicFile.WriteAllText(Path.Combine(dir, "lights.json"),
            Describe(scene, t).ToJsonString(new JsonSerializerOptions { WriteIndented = true }));
        done($"{TransferFormat.Folder}/lights.json");
    }

    /// <summary>lights.json of a path render (the whole film's: a shard's is the same).</summary>
    public static JsonObject Describe(Scene scene, PathTransfer t)
    {
        var grid = PathIntegrator.GridOf(scene, t.SpectralGrid);
        var lights = new JsonArray();
        var groups = new JsonArray();
        for (int k = 0; k < scene.Lights.Count; k++)
        {
            lights.Add((JsonNode)TransferFormat.LightEntry(scene, k));
            groups.Add((JsonNode)$"light {scene.Lights[k].Name}");
        }
        groups.Add((JsonNode)"emitters and sky");
        string shifted = t.Shift.IsEmpty ? "" : ", plus for f in the shift's emission sub-bands sum over lights k and c < C of " +
            "shift[y, x, k, f - row0, c] * E_k,(column0 + c)";
        var json = new JsonObject
        {
            ["kind"] = Kind,
            ["version"] = Version,
            ["layout"] = "radiance on the fine grid L_f(pixel) = transfer[y, x, K, f] + sum over lights k < K of " +
                "transfer[y, x, k, f] * E_k,f" + shifted + " (E_k: light k's spectrum x intensity, exact sub-band means); " +
                "band b = mean of its sub-bands; XYZ integrated on the fine grid",
            ["width"] = t.FilmWidth,
            ["height"] = t.FilmHeight,
            ["bands"] = t.Bands,
            ["spectral_grid_nm"] = t.SpectralGrid,
            ["sub_bands"] = t.SubBands,
            ["sub_band_edges_nm"] = new JsonArray(grid.Lower.Append(grid.Upper[^1]).Select(x => (JsonNode)JsonValue.Create(x)).ToArray()),
            ["lights"] = lights,
            ["groups"] = groups,
            ["files"] = new JsonObject
            {
                ["transfer"] = "transfer.npy: float32 [H, W, K + 1, F]: light k's path weights T_k,f (radiance per unit of its spectrum x "
                    + "intensity), then the emitters' and sky's radiance (W m^-2 sr^-1 nm^-1)",
                ["ids"] = "ids.npy: float32 [H, W, 3]: object index + 1 seen by the centre ray (0 = background), then the lit mask " +
                    "(bit k = light k reaches that point) as its low and high 16 bits",
            },
        };
        if (!t.Shift.IsEmpty)
        {
            var sh = t.Shift;
            json["shift"] = new JsonObject
            {
                ["emission_sub_bands"] = new JsonArray(sh.Row0, sh.Rows),
                ["excitation_sub_bands"] = new JsonArray(sh.Column0, sh.Columns),
                ["emission_nm"] = new JsonArray(grid.Lower[sh.Row0], grid.Upper[sh.Row0 + sh.Rows - 1]),
                ["excitation_nm"] = new JsonArray(grid.Lower[sh.Column0], grid.Upper[sh.Column0 + sh.Columns - 1]),
            };
            json["files"]!["shift"] = "shift.npy: float32 [H, W, K, R, C]: light k's paths through a fluorescent shift, from excitation " +
                "sub-band column0 + c to emission sub-band row0 + r " +
                "(shift.emission_sub_bands = [row0, R], excitation_sub_bands = [column0, C])";
        }
        return json;
    }

    /// <summary>The shift block lights.json declares (empty when it has none), checked against <paramref name="subBands"/>.</summary>
    internal static ShiftSpan ReadShift(JsonFields r, JsonObject json, int subBands)
    {
        if (r.OptObject(json, "shift", "$") is not { } shift) return default;
        int[] Range(string key)
        {
            var v = r.Numbers(shift, key, "$.shift", 2, 0, subBands);
            if (v.Any(x => x != Math.Floor(x)) || v[1] < 1 || v[0] + v[1] > subBands)
                throw r.Bad($"$.shift.{key}", $"is not [first, count] of the {subBands} sub-bands");
            return [(int)v[0], (int)v[1]];
        }
        var rows = Range("emission_sub_bands");
        var columns = Range("excitation_sub_bands");
        return new ShiftSpan(rows[0], rows[1], columns[0], columns[1]);
    }


    /// <summary>Reads lights/ of a path render back, checked against <paramref name="scene"/> (sizes, lights, grid).</summary>
    public static PathTransfer Read(string outDir, Scene scene)
    {
        var dir = Path.Combine(outDir, TransferFormat.Folder);
        var jsonPath = Path.Combine(dir, "lights.json");
        var json = JsonFields.ParseFile(jsonPath, "lights.json", Damaged);
        var r = new JsonFields(jsonPath, Damaged);
        int width = r.Int(json, "width", "$", 1, 32768), height = r.Int(json, "height", "$", 1, 32768),
            bands = r.Int(json, "bands", "$", 1, 100_000);
        if (bands != scene.Bands) throw r.Bad("$.bands", $"is {bands}, but the scene rebuilds with {scene.Bands} bands");
        int k = scene.Lights.Count;
        r.Array(json, "lights", "$", k);
        double gridWidth = r.Number(json, "spectral_grid_nm", "$", 1, 1000);
        int sub = r.Int(json, "sub_bands", "$", 1, 1 << 20);
        var grid = PathIntegrator.GridOf(scene, gridWidth);
        if (grid.Count != sub) throw r.Bad("$.sub_bands", $"is {sub}, but the scene's grid of {gridWidth} nm has {grid.Count} sub-bands");
        if (json["sub_band_edges_nm"] is not null)
        {   // an adaptive grid has as many sub-bands as the uniform one: the edges say which the render carried
            var edges = r.Numbers(json, "sub_band_edges_nm", "$", sub + 1);
            for (int f = 0; f <= sub; f++)
                if (Math.Abs(edges[f] - (f < sub ? grid.Lower[f] : grid.Upper[^1])) > 1e-6)
                    throw r.Bad($"$.sub_band_edges_nm[{f}]", string.Create(CultureInfo.InvariantCulture,
                        $"is {edges[f]} nm, but the scene's grid has an edge at {(f < sub ? grid.Lower[f] : grid.Upper[^1])} nm"));
        }
        int version = r.OptInt(json, "version", "$", 1, int.MaxValue) ?? 1;
        if (version > Version)
            throw new InputException($"{jsonPath}: $.version",
                $"is {version}: a newer spectral wrote these lights/ (this one reads versions 1–{Version})",
                "relight it with the spectral that rendered it, or render the folder again");
        var shift = ReadShift(r, json, sub);
        if (!shift.IsEmpty && k == 0) throw r.Bad("$.shift", "is given, but the transfer has no lights");

        float[] Load(string file, int[] expected)
        {
            var path = Path.Combine(dir, file);
            if (!File.Exists(path))
                throw new InputException(outDir, $"misses {TransferFormat.Folder}/{file}", "render again with the lights output");
            using var s = new FileStream(path, FileMode.Open, FileAccess.Read, FileShare.Read, bufferSize: 1);
            var (shape, data) = NpyReader.Read(s, path);
            if (!shape.SequenceEqual(expected))
                throw new InputException(path, $"has shape ({string.Join(", ", shape)}), lights.json says ({string.Join(", ", expected)})",
                    "the folder mixes two renders; render again");
            return data;
        }
        var data = Load(TransferFile, [height, width, k + 1, sub]);
        var blocks = shift.IsEmpty ? [] : Load(ShiftFile, [height, width, k, shift.Rows, shift.Columns]);
        var ids = Load(IdsFile, [height, width, 3]);
        var objectIds = new int[width * height];
        var lit = new uint[objectIds.Length];
        for (int i = 0; i < objectIds.Length; i++)
        {
            float id = ids[3 * i], low = ids[3 * i + 1], high = ids[3 * i + 2];
            if (!(id >= 0 && id <= scene.Objects.Count && id == MathF.Floor(id)))
                throw new InputException(Path.Combine(dir, IdsFile),
                    $"pixel {i % width},{i / width}: object {id} is not 0 (background) or one of the scene's {scene.Objects.Count}",
                    "the light-transfer files are damaged: render the folder again");
            if (!(low >= 0 && low <= 0xFFFF && low == MathF.Floor(low) && high >= 0 && high <= 0xFFFF && high == MathF.Floor(high)))
                throw new InputException(Path.Combine(dir, IdsFile),
                    $"pixel {i % width},{i / width}: lit mask halves {low}, {high} are not whole numbers 0–65535",
                    "the light-transfer files are damaged: render the folder again");
            objectIds[i] = (int)id - 1;
            lit[i] = (uint)low | (uint)high << 16;
        }
        return new PathTransfer
        {
            FilmWidth = width,
            FilmHeight = height,
            Region = PixelRect.Whole(width, height),
            Bands = bands,
            Lights = k,
            SpectralGrid = gridWidth,
            SubBands = sub,
            Data = data,
            Shift = shift,
            Blocks = blocks,
            ObjectIds = objectIds,
            ReadFromFiles = true,
            LitMasks = lit,
        };
    }
}
