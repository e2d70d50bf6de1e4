using System.Globalization;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.Whitted;

/// <summary>
/// The per-light transfer outputs (<c>--formats …,lights</c> or <c>output.light_groups</c>), in <c>lights/</c>:
/// <list type="bullet">
/// <item><c>lights.json</c>: the layout, the lights (name, spectrum, band values I_k,b = spectrum × intensity) and the
/// components c in file order (light, lobe, material, the mirror/transmit chain, and their band values P_c,b and XYZ in
/// this render: the scene's term table times the chain's weights; relighting rebuilds them from the new spectra).</item>
/// <item><c>factors.npy</c> (float32 [nnz]) and <c>pixels.npy</c> (int32 [nnz]): component c's geometric factors F_c and
/// the pixels they belong to (y·W + x, ascending) are entries offset … offset + count − 1 (<c>components[c].offset</c>,
/// <c>.count</c> in lights.json): a sparse layout, since most components (a light's term seen through a mirror or
/// glass) cover few pixels.</item>
/// <item><c>centre.npy</c>: float32 2K × H × W, per light the centre ray's diffuse then specular factor at its first
/// hit; <c>ids.npy</c>: float32 3 × H × W, the object index + 1 seen by the centre ray (0 = background), the lit mask
/// (bit k: light k reaches the point; exact for the first 24 lights) and 1 where a path met a coloured mirror or
/// transmittance (the pixel's colour is then eq. 3 on its band values, as in the render).</item>
/// </list>
/// A pixel's band values are L_b = Σ_c F_c · P_c,b and its colour Σ_c F_c · XYZ_c (<see cref="WhittedTransfer"/>).
/// </summary>
internal static class WhittedTransferFiles
{
    public const string Folder = TransferFormat.Folder;

    /// <summary>The Whitted transfer's format: its lights.json names no kind (the first format); eq. 2's terms for the camera.</summary>
    public static readonly TransferFormat Format = new TermFormat();

    sealed class TermFormat : TransferFormat
    {
        public override string? Kind => null;
        public override string Integrator => "whitted";
        public override CameraRoute Route => CameraRoute.Terms;

        /// <summary>Its factors are known only once traced; its textured terms' texel samples (S per term and pixel, issue 26)
        /// are counted for a first hit.</summary>
        public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene) =>
            WhittedTransfer.TexelBytes(scene) is > 0 and var texels
            ? [("per-light transfer: texel samples of textured terms", texels)]
            : [];

        public override ILightTransfer Read(string outDir, Scene scene) => WhittedTransferFiles.Read(outDir, scene);
    }

    /// <summary>The four arrays every transfer has, in the order written.</summary>
    public static readonly IReadOnlyList<string> Arrays = ["factors.npy", "pixels.npy", "centre.npy", "ids.npy"];

    /// <summary>The texel arrays of a transfer with textured terms (issue 26).</summary>
    public const string TexelsFile = "texels.npy", CentreTexelsFile = "centre-texels.npy";

    /// <summary>The arrays of <paramref name="t"/>, in the order written: the four, and the texel samples when it has
    /// textured terms.</summary>
    public static IReadOnlyList<string> ArraysOf(WhittedTransfer t) =>
        t.Texels is null ? Arrays : [.. Arrays, TexelsFile, CentreTexelsFile];

    public static void Write(Scene scene, WhittedTransfer t, string outDir, Action<string> done)
    {
        var dir = Path.Combine(outDir, Folder);
        Directory.CreateDirectory(dir);
        if (t.StoredIn is { } from)
        {
            // Read from files that are byte for byte these arrays' encoding: copied (in the kernel), not encoded again.
            foreach (var f in ArraysOf(t))
            {
                File.Copy(Path.Combine(from, Folder, f), Path.Combine(dir, f));
                done($"{Folder}/{f}");
            }
        }
        else
        {
            WriteArrays(t, dir, done);
            if (t.Texels is not null) WriteTexels(scene, t, dir, done);
        }
        AtomicFile.WriteAllText(Path.Combine(dir, "lights.json"),
            Describe(scene, t).ToJsonString(new JsonSerializerOptions { WriteIndented = true }));
        done($"{Folder}/lights.json");
    }

    static void WriteArrays(WhittedTransfer t, string dir, Action<string> done)
    {
        int n = t.Width * t.Height;
        int nnz = t.Factors.Sum(f => f.Length);
        var factors = new float[nnz];
        var pixels = new int[nnz];
        for (int c = 0, at = 0; c < t.Components.Length; at += t.Factors[c].Length, c++)
        {
            t.Factors[c].CopyTo(factors, at);
            t.Pixels[c].CopyTo(pixels, at);
        }
        AtomicFile.Write(Path.Combine(dir, "factors.npy"), s => NpyWriter.Write(s, [nnz], factors));
        done($"{Folder}/factors.npy");
        AtomicFile.Write(Path.Combine(dir, "pixels.npy"), s => NpyInt32.Write(s, [nnz], pixels));
        done($"{Folder}/pixels.npy");
        int k = t.CentreDiffuse.Length;
        var centre = new float[2 * k * n];
        for (int i = 0; i < k; i++) { t.CentreDiffuse[i].CopyTo(centre, 2 * i * n); t.CentreSpecular[i].CopyTo(centre, (2 * i + 1) * n); }
        AtomicFile.Write(Path.Combine(dir, "centre.npy"), s => NpyWriter.Write(s, [2 * k, t.Height, t.Width], centre));
        done($"{Folder}/centre.npy");
        var ids = new float[3 * n];
        for (int i = 0; i < n; i++) { ids[i] = t.ObjectIds[i] + 1; ids[n + i] = t.LitMasks[i]; ids[2 * n + i] = t.Fallback[i] ? 1 : 0; }
        AtomicFile.Write(Path.Combine(dir, "ids.npy"), s => NpyWriter.Write(s, [3, t.Height, t.Width], ids));
        done($"{Folder}/ids.npy");
    }

    /// <summary>
    /// texels.npy: float32 [Σ_c count_c · S_c], each textured component's entries' texel samples in the order of its factors;
    /// centre-texels.npy: float32 [Σ S_d + S_s], for each pixel (ascending) whose centre ray saw a textured material, its
    /// filtered samples of that material's diffuse texture, then of its specular texture.
    /// </summary>
    static void WriteTexels(Scene scene, WhittedTransfer t, string dir, Action<string> done)
    {
        var texels = new float[t.Texels!.Sum(v => (long)(v?.Length ?? 0))];
        long at = 0;
        foreach (var v in t.Texels!) if (v is not null) { v.CopyTo(texels, at); at += v.Length; }
        AtomicFile.Write(Path.Combine(dir, TexelsFile), s => NpyWriter.Write(s, [texels.Length], texels));
        done($"{Folder}/{TexelsFile}");
        var centre = new float[CentreTexelCount(scene, t.ObjectIds)];
        at = 0;
        for (int i = 0; i < t.ObjectIds.Length; i++)
        {
            int w = CentreTexelsOf(scene, t.ObjectIds[i]);
            t.CentreTexels.AsSpan(i * t.CentreWidth, w).CopyTo(centre.AsSpan((int)at));
            at += w;
        }
        AtomicFile.Write(Path.Combine(dir, CentreTexelsFile), s => NpyWriter.Write(s, [centre.Length], centre));
        done($"{Folder}/{CentreTexelsFile}");
    }

    /// <summary>The centre texels a pixel whose centre ray saw object <paramref name="id"/> (−1: none) has: its material's
    /// diffuse and specular textures' samples.</summary>
    static int CentreTexelsOf(Scene scene, int id)
    {
        if (id < 0) return 0;
        var m = scene.Materials[scene.Objects[id].Material];
        return (m.DiffuseTexture?.Texture.Samples ?? 0) + (m.SpecularTexture?.Texture.Samples ?? 0);
    }

    static long CentreTexelCount(Scene scene, int[] ids) => ids.Sum(id => (long)CentreTexelsOf(scene, id));

    /// <summary>Whether <paramref name="path"/> is <paramref name="preamble"/> followed by exactly <paramref name="dataBytes"/> bytes of
    /// data.</summary>
    static bool Canonical(string path, byte[] preamble, long dataBytes)
    {
        if (new FileInfo(path).Length != preamble.Length + dataBytes) return false;
        using var s = File.OpenRead(path);
        var head = new byte[preamble.Length];
        s.ReadExactly(head);
        return head.AsSpan().SequenceEqual(preamble);
    }

    /// <summary>The light band values I_k,b (spectrum × intensity) of the scene's lights, unpadded.</summary>
    public static JsonObject Describe(Scene scene, WhittedTransfer t)
    {
        var lights = new JsonArray();
        for (int k = 0; k < scene.Lights.Count; k++) lights.Add((JsonNode)TransferFormat.LightEntry(scene, k));
        var comps = new JsonArray();
        var tables = new TermTables(scene, TexelContent.None);
        var p = new float[scene.PaddedBands];
        long texelOffset = 0;
        for (int c = 0, offset = 0; c < t.Components.Length; offset += t.Factors[c].Length, c++)
        {
            var comp = t.Components[c];
            comp.BandValues(tables, p);
            var texture = comp.Texture(scene);
            JsonObject? texels = null;
            if (texture is not null && t.Texels?[c] is { } v)
            {
                texels = new JsonObject
                {
                    ["samples"] = texture.Samples,
                    ["offset"] = texelOffset,
                    ["texture"] = Path.GetFileName(texture.Source),
                };
                texelOffset += v.Length;
            }
            var entry = new JsonObject
            {
                ["index"] = c,
                ["key"] = comp.Key,
                ["offset"] = offset,
                ["count"] = t.Factors[c].Length,
                ["merged_chains"] = t.Merged[c],
                ["light"] = comp.Light,
                ["lobe"] = TransferComponent.LobeName(comp.Lobe),
                ["follows_light"] = comp.FollowsLight,
                ["material"] = comp.Material < 0 ? null : scene.Materials[comp.Material].Name,
                ["chain"] = new JsonArray(comp.Chain.Select(x => (JsonNode)new JsonObject
                { ["material"] = scene.Materials[x.Material].Name, ["weight"] = x.Transmit ? "transmit" : "mirror" }).ToArray()),
                ["band_values"] = TransferFormat.Values(p.AsSpan(0, scene.Bands)),
                ["xyz"] = TransferFormat.Values(p.AsSpan(scene.Bands, 3)),
                ["coloured_chain"] = comp.Coloured(tables),
                ["band"] = comp.Band >= 0 ? comp.Band + 1 : null,   // after a dispersive split: the one band (from 1) it reaches
            };
            // A textured term: its entries' texel samples in texels.npy (band_values, xyz: the texture's mean); absent otherwise,
            // so a transfer without textures is written as before.
            if (texels is not null) entry["texels"] = texels;
            comps.Add((JsonNode)entry);
        }
        var files = new JsonObject
        {
            ["factors"] = "factors.npy: float32 [nnz], the factors of component c at entries offset .. offset + count - 1",
            ["pixels"] = "pixels.npy: int32 [nnz], the pixel (y * width + x) of each factor, ascending within a component",
            ["centre"] = "centre.npy: float32 [2K, H, W], light k's centre-ray diffuse (2k) and specular (2k+1) factor",
            ["ids"] = "ids.npy: float32 [3, H, W], object index + 1 (0 = background), lit mask, "
                + "colour fallback (1: eq. 3 on the band values)",
        };
        if (t.Texels is not null)
        {
            files["texels"] = "texels.npy: float32, a textured component c's entry j (j from 0 to count - 1) has "
                + "S = c.texels.samples values V at c.texels.offset + j * S: the sum over the pixel's terms of factor * the "
                + "filtered texel samples (at the texture's wavelengths); its band values are sum_i V_i * (E * tent_i) band "
                + "means and XYZ, tent_i the texture's linear interpolant of sample i, plus factor * a fluorescent shift, "
                + "times the chain's weights";
            files["centre_texels"] = "centre-texels.npy: float32, for each pixel (ascending) whose centre ray saw a textured "
                + "material, its filtered diffuse texture samples then its specular texture samples (the highlight mask's Y)";
        }
        var materials = new JsonArray(scene.Materials.Select(mt => (JsonNode)new JsonObject
        {
            ["name"] = mt.Name,
            ["diffuse_spectrum"] = mt.DiffuseSpectrum?.Name,
            ["diffuse_band_values"] = TransferFormat.Values(mt.Diffuse.AsSpan(0, scene.Bands)),
        }).ToArray());
        return new JsonObject
        {
            ["layout"] = "L_b(pixel) = sum over components c and entries j in [c.offset, c.offset + c.count) with pixels[j] = pixel of "
                + "factors[j] * c.band_values[b]; the pixel's XYZ the same sum of factors[j] * c.xyz (eq. 3 on L_b where "
                + "ids[2] marks a colour fallback)",
            ["width"] = t.Width,
            ["height"] = t.Height,
            ["bands"] = t.Bands,
            ["band_scheme"] = scene.Integration.ToString().ToLowerInvariant(),
            ["exact_for"] = "every band scheme: a component's band values and XYZ are the scene's term tables (exact band means of E·m and "
                + "their exact XYZ under 'exact') times the chain's weights, as the integrator multiplies them",
            ["lights"] = lights,
            ["materials"] = materials,
            ["components"] = comps,
            ["files"] = files,
        };
    }

    const string Damaged = "lights/lights.json is not as a render writes it: render the folder again with the lights output";

    /// <summary>lights.json's layout: the image and band counts, the components and where their entries lie in factors.npy.</summary>
    public sealed record Layout(int Width, int Height, int Bands, TransferComponent[] Components, (int Offset, int Count)[] Offsets,
        int[] Merged, long Entries)
    {
        /// <summary>Per component, where its texel samples start in texels.npy and how many per entry (S); null: a spectrum's
        /// term.</summary>
        public (long Offset, int Samples)?[] Texels { get; init; } = [];
        /// <summary>How many floats texels.npy holds (0: no textured component).</summary>
        public long TexelFloats { get; init; }
    }

    /// <summary>
    /// lights.json checked against the scene it is read with: sizes in range, one entry per scene light, each component's
    /// light, lobe, materials (by name), chain (at most <see cref="WhittedTransfer.MaxChain"/>) and band valid, its entries
    /// [offset, offset + count) inside the stored total, which fits one array.
    /// </summary>
    public static Layout ParseLayout(JsonObject json, string jsonPath, Scene scene)
    {
        var r = new JsonFields(jsonPath, Damaged);
        int width = r.Int(json, "width", "$", 1, 32768), height = r.Int(json, "height", "$", 1, 32768),
            bands = r.Int(json, "bands", "$", 1, 100_000);
        if (bands != scene.Bands) throw r.Bad("$.bands", $"is {bands}, but the render has {scene.Bands} bands");
        int k = scene.Lights.Count;
        r.Array(json, "lights", "$", k);
        var materialIndex = new Dictionary<string, int>(StringComparer.Ordinal);
        for (int i = 0; i < scene.Materials.Count; i++) materialIndex.TryAdd(scene.Materials[i].Name, i);
        int Mat(JsonNode? node, string at)
        {
            string name = r.String(node, at);
            return materialIndex.TryGetValue(name, out int i) ? i
                : throw r.Bad(at, $"names material {MessageText.Quote(name)}, which the scene does not have");
        }
        var nodes = r.Array(json, "components", "$", max: 1 << 24);
        var comps = new TransferComponent[nodes.Count];
        var offsets = new (int, int)[nodes.Count];
        var merged = new int[nodes.Count];
        var texels = new (long, int)?[nodes.Count];
        long entries = 0, texelFloats = 0;
        for (int c = 0; c < comps.Length; c++)
        {
            string at = $"$.components[{c}]";
            var o = r.Object(nodes[c], at);
            string lobeName = r.String(o, "lobe", at);
            TransferLobe lobe = lobeName switch
            {
                "diffuse" or "specular" or "ambient" or "global-ambient" or "background" => TransferComponent.ParseLobe(lobeName),
                _ => throw r.Bad($"{at}.lobe",
                    $"is {MessageText.Quote(lobeName)}, not diffuse, specular, ambient, global-ambient or background"),
            };
            bool ofLight = lobe is TransferLobe.Diffuse or TransferLobe.Specular or TransferLobe.Ambient;
            int light = r.Int(o, "light", at, ofLight ? 0 : -1, ofLight ? k - 1 : -1);
            int material = lobe == TransferLobe.Background
                ? o["material"] is null ? -1 : throw r.Bad($"{at}.material", "is given for the background, which has no material")
                : Mat(o["material"], $"{at}.material");
            var chainNodes = r.Array(o, "chain", at, max: WhittedTransfer.MaxChain);
            var chain = new (int, bool)[chainNodes.Count];
            for (int i = 0; i < chain.Length; i++)
            {
                string ca = $"{at}.chain[{i}]";
                var x = r.Object(chainNodes[i], ca);
                string weight = r.String(x, "weight", ca);
                if (weight is not ("mirror" or "transmit"))
                    throw r.Bad($"{ca}.weight", $"is {MessageText.Quote(weight)}, not mirror or transmit");
                chain[i] = (Mat(x["material"], $"{ca}.material"), weight == "transmit");
            }
            int band = r.OptInt(o, "band", at, 1, bands) is { } b ? b - 1 : -1;
            comps[c] = new TransferComponent(light, lobe, material, chain) { Band = band };
            int offset = r.Int(o, "offset", at, 0), count = r.Int(o, "count", at, 0, width * height);
            if (offset + (long)count > Array.MaxLength)
                throw r.Bad($"{at}.count", $"puts entries beyond {Array.MaxLength}, the most one array holds");
            offsets[c] = (offset, count);
            entries += count;
            merged[c] = r.OptInt(o, "merged_chains", at, 1) ?? 1;
            // A textured term (issue 26) holds its entries' texel samples; the scene says which terms are textured.
            var texture = comps[c].Texture(scene);
            var tx = r.OptObject(o, "texels", at);
            if (texture is null && tx is not null)
                throw r.Bad($"{at}.texels", "is given for a term the scene's material gives by a spectrum, not a texture");
            if (texture is not null)
            {
                if (tx is null)
                    throw r.Bad(at, $"is material {MessageText.Quote(scene.Materials[material].Name)}'s textured term but has no texels");
                int samples = r.Int(tx, "samples", $"{at}.texels", texture.Samples, texture.Samples);
                long to = r.Long(tx["offset"], $"{at}.texels.offset", 0, Array.MaxLength);
                texels[c] = (to, samples);
                texelFloats += (long)count * samples;
            }
        }
        for (int c = 0; c < comps.Length; c++)
            if (texels[c] is { } tc && tc.Item1 + (long)offsets[c].Item2 * tc.Item2 > texelFloats)
                throw r.Bad($"$.components[{c}].texels.offset", $"puts samples beyond the {texelFloats} stored");
        if (texelFloats > Array.MaxLength)
            throw r.Bad("$.components", $"hold {texelFloats} texel samples in all, more than one array holds");
        if (entries > Array.MaxLength) throw r.Bad("$.components", $"count {entries} entries in all, more than one array holds");
        for (int c = 0; c < comps.Length; c++)
            if (offsets[c].Item1 + (long)offsets[c].Item2 > entries)
                throw r.Bad($"$.components[{c}].offset",
                    $"entries {offsets[c].Item1}…{offsets[c].Item1 + (long)offsets[c].Item2 - 1} lie outside the {entries} stored");
        if (2L * k * width * height > Array.MaxLength)
            throw r.Bad("$.width", $"{width}×{height} pixels × {k} lights is more than one array holds");
        return new Layout(width, height, bands, comps, offsets, merged, entries) { Texels = texels, TexelFloats = texelFloats };
    }

    /// <summary>Reads lights/ back into a transfer whose components refer to <paramref name="scene"/>'s materials by name.</summary>
    public static WhittedTransfer Read(string outDir, Scene scene)
    {
        var dir = Path.Combine(outDir, Folder);
        var jsonPath = Path.Combine(dir, "lights.json");
        if (!File.Exists(jsonPath))
            throw new InputException(outDir, "has no per-light outputs (lights/lights.json)",
                "render with --formats …,lights or \"output\": { \"light_groups\": true }");
        var layout = ParseLayout(JsonFields.ParseFile(jsonPath, "lights.json", Damaged), jsonPath, scene);
        int width = layout.Width, height = layout.Height, bands = layout.Bands;
        int n = width * height;
        var comps = layout.Components;

        float[] Load(string file, int[] expected)
        {
            var path = Path.Combine(dir, file);
            if (!File.Exists(path)) throw new InputException(outDir, $"misses {Folder}/{file}", "render again with the lights output");
            using var s = new FileStream(path, FileMode.Open, FileAccess.Read, FileShare.Read, bufferSize: 1);   // one read into the array
            var (shape, data) = NpyReader.Read(s, path);
            if (!shape.SequenceEqual(expected))
                throw new InputException(path, $"has shape ({string.Join(", ", shape)}), lights.json says ({string.Join(", ", expected)})",
                    "the folder mixes two renders; render again");
            return data;
        }
        long nnz = layout.Entries;
        var f = Load("factors.npy", [(int)nnz]);
        int[] pix;
        {
            var path = Path.Combine(dir, "pixels.npy");
            if (!File.Exists(path)) throw new InputException(outDir, $"misses {Folder}/pixels.npy", "render again with the lights output");
            using var s = new FileStream(path, FileMode.Open, FileAccess.Read, FileShare.Read, bufferSize: 1);
            var (shape, data) = NpyInt32.Read(s, path);
            if (shape.Length != 1 || shape[0] != nnz)
                throw new InputException(path, $"holds {string.Join("×", shape)} entries, lights.json says {nnz}",
                    "the folder mixes two renders; render again");
            pix = data;
        }
        foreach (int p in pix)
            if ((uint)p >= (uint)n)
                throw new InputException(Path.Combine(dir, "pixels.npy"), $"pixel {p} is outside the {width}×{height} image",
                    "the light-transfer files are damaged: render the folder again");
        var offsets = layout.Offsets;
        foreach (var (o, c) in offsets)
        {
            for (int j = o + 1; j < o + c; j++)
                if (pix[j] <= pix[j - 1])
                    throw new InputException(Path.Combine(dir, "pixels.npy"), $"entry {j}: pixels of a component must ascend",
                        "render again");
        }
        int k = scene.Lights.Count;
        var centre = Load("centre.npy", [2 * k, height, width]);
        var ids = Load("ids.npy", [3, height, width]);
        var objectIds = new int[n];
        var litMasks = new uint[n];
        var fallback = new bool[n];
        // Writing the transfer back gives the same ids.npy when every value is one the conversions keep.
        bool idsKept = true;
        for (int i = 0; i < n; i++)
        {
            if (!(ids[i] >= 0 && ids[i] <= scene.Objects.Count && ids[i] == MathF.Floor(ids[i])))
                throw new InputException(Path.Combine(dir, "ids.npy"),
                    $"pixel {i % width},{i / width}: object {ids[i]} is not 0 (background) or one of the scene's {scene.Objects.Count}",
                    "the light-transfer files are damaged: render the folder again");
            objectIds[i] = (int)ids[i] - 1; litMasks[i] = (uint)ids[n + i]; fallback[i] = ids[2 * n + i] != 0;
            idsKept &= objectIds[i] + 1 == ids[i] && litMasks[i] == ids[n + i] && (fallback[i] ? 1f : 0f) == ids[2 * n + i];
        }
        // Textured terms: their entries' texel samples, and the centre rays' (issue 26).
        float[]?[]? texels = null;
        float[]? centreTexels = null;
        int centreWidth = 0;
        bool textured = layout.Texels.Any(x => x is not null);
        if (textured)
        {
            var all = Load(TexelsFile, [(int)layout.TexelFloats]);
            texels = new float[]?[comps.Length];
            for (int c = 0; c < comps.Length; c++)
                if (layout.Texels[c] is { } tc) texels[c] = all.AsSpan((int)tc.Offset, offsets[c].Count * tc.Samples).ToArray();
            centreWidth = WhittedTransfer.CentreWidthOf(scene);
            var compact = Load(CentreTexelsFile, [(int)CentreTexelCount(scene, objectIds)]);
            centreTexels = new float[(long)n * centreWidth];
            for (int i = 0, at = 0; i < n; i++)
            {
                int w = CentreTexelsOf(scene, objectIds[i]);
                compact.AsSpan(at, w).CopyTo(centreTexels.AsSpan(i * centreWidth));
                at += w;
            }
        }
        // … and the same factors.npy and pixels.npy when the components' entries follow each other in order.
        bool contiguous = true;
        for (int c = 0, at = 0; c < offsets.Length; at += offsets[c].Count, c++) contiguous &= offsets[c].Offset == at;
        for (long c = 0, at = 0; c < comps.Length; c++)
            if (layout.Texels[c] is { } tc) { contiguous &= tc.Offset == at; at += (long)offsets[c].Count * tc.Samples; }
        bool canonical = idsKept && contiguous
            && Canonical(Path.Combine(dir, "factors.npy"), NpyWriter.Preamble([(int)nnz]), 4 * nnz)
            && Canonical(Path.Combine(dir, "pixels.npy"), NpyInt32.Preamble([(int)nnz]), 4 * nnz)
            && Canonical(Path.Combine(dir, "centre.npy"), NpyWriter.Preamble([2 * k, height, width]), 4L * centre.Length)
            && Canonical(Path.Combine(dir, "ids.npy"), NpyWriter.Preamble([3, height, width]), 4L * ids.Length)
            && (!textured
                || (Canonical(Path.Combine(dir, TexelsFile), NpyWriter.Preamble([(int)layout.TexelFloats]), 4 * layout.TexelFloats)
                && Canonical(Path.Combine(dir, CentreTexelsFile), NpyWriter.Preamble([(int)CentreTexelCount(scene, objectIds)]),
                    4 * CentreTexelCount(scene, objectIds))));
        return new WhittedTransfer
        {
            Width = width,
            Height = height,
            Bands = bands,
            Grid = scene.Grid,
            Components = comps,
            Factors = offsets.Select(o => f.AsSpan(o.Offset, o.Count).ToArray()).ToArray(),
            Pixels = offsets.Select(o => pix.AsSpan(o.Offset, o.Count).ToArray()).ToArray(),
            Merged = layout.Merged,
            CentreDiffuse = Enumerable.Range(0, k).Select(i => centre.AsSpan(2 * i * n, n).ToArray()).ToArray(),
            CentreSpecular = Enumerable.Range(0, k).Select(i => centre.AsSpan((2 * i + 1) * n, n).ToArray()).ToArray(),
            ObjectIds = objectIds,
            LitMasks = litMasks,
            Fallback = fallback,
            Rays = new RayCounters(),
            Texels = texels,
            CentreTexels = centreTexels,
            CentreWidth = centreWidth,
            StoredIn = canonical ? Path.GetFullPath(outDir) : null,
        };
    }
}
