using System.Globalization;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Output;

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
/// A pixel's band values are L_b = Σ_c F_c · P_c,b and its colour Σ_c F_c · XYZ_c (<see cref="LightTransfer"/>).
/// </summary>
public static class LightTransferFiles
{
    public const string Folder = "lights";

    /// <summary>The four arrays, in the order written.</summary>
    public static readonly IReadOnlyList<string> Arrays = ["factors.npy", "pixels.npy", "centre.npy", "ids.npy"];

    public static void Write(Scene scene, LightTransfer t, string outDir, Action<string> done)
    {
        var dir = Path.Combine(outDir, Folder);
        Directory.CreateDirectory(dir);
        if (t.StoredIn is { } from)
        {
            // Read from files that are byte for byte these arrays' encoding: copied (in the kernel), not encoded again.
            foreach (var f in Arrays)
            {
                File.Copy(Path.Combine(from, Folder, f), Path.Combine(dir, f));
                done($"{Folder}/{f}");
            }
        }
        else WriteArrays(t, dir, done);
        AtomicFile.WriteAllText(Path.Combine(dir, "lights.json"), Describe(scene, t).ToJsonString(new JsonSerializerOptions { WriteIndented = true }));
        done($"{Folder}/lights.json");
    }

    static void WriteArrays(LightTransfer t, string dir, Action<string> done)
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

    /// <summary>Whether <paramref name="path"/> is <paramref name="preamble"/> followed by exactly <paramref name="dataBytes"/> bytes of data.</summary>
    static bool Canonical(string path, byte[] preamble, long dataBytes)
    {
        if (new FileInfo(path).Length != preamble.Length + dataBytes) return false;
        using var s = File.OpenRead(path);
        var head = new byte[preamble.Length];
        s.ReadExactly(head);
        return head.AsSpan().SequenceEqual(preamble);
    }

    /// <summary>The light band values I_k,b (spectrum × intensity) of the scene's lights, unpadded.</summary>
    public static JsonObject Describe(Scene scene, LightTransfer t)
    {
        var lights = new JsonArray();
        for (int k = 0; k < scene.Lights.Count; k++)
        {
            var l = scene.Lights[k];
            lights.Add((JsonNode)new JsonObject
            {
                ["index"] = k,
                ["name"] = l.Name,
                ["kind"] = l.Type,
                ["spectrum"] = l.Spectrum?.Name,
                ["band_values"] = Arr(l.Intensity.AsSpan(0, scene.Bands)),
            });
        }
        var comps = new JsonArray();
        var tables = new TermTables(scene);
        var p = new float[scene.PaddedBands];
        for (int c = 0, offset = 0; c < t.Components.Length; offset += t.Factors[c].Length, c++)
        {
            var comp = t.Components[c];
            comp.BandValues(tables, p);
            comps.Add((JsonNode)new JsonObject
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
                ["band_values"] = Arr(p.AsSpan(0, scene.Bands)),
                ["xyz"] = Arr(p.AsSpan(scene.Bands, 3)),
                ["coloured_chain"] = comp.Coloured(tables),
                ["band"] = comp.Band >= 0 ? comp.Band + 1 : null,   // after a dispersive split: the one band (from 1) it reaches
            });
        }
        var materials = new JsonArray(scene.Materials.Select(mt => (JsonNode)new JsonObject
        {
            ["name"] = mt.Name,
            ["diffuse_spectrum"] = mt.DiffuseSpectrum?.Name,
            ["diffuse_band_values"] = Arr(mt.Diffuse.AsSpan(0, scene.Bands)),
        }).ToArray());
        return new JsonObject
        {
            ["layout"] = "L_b(pixel) = sum over components c and entries j in [c.offset, c.offset + c.count) with pixels[j] = pixel of factors[j] * c.band_values[b]; the pixel's XYZ the same sum of factors[j] * c.xyz (eq. 3 on L_b where ids[2] marks a colour fallback)",
            ["width"] = t.Width,
            ["height"] = t.Height,
            ["bands"] = t.Bands,
            ["band_scheme"] = scene.Integration.ToString().ToLowerInvariant(),
            ["exact_for"] = "every band scheme: a component's band values and XYZ are the scene's term tables (exact band means of E·m and their exact XYZ under 'exact') times the chain's weights, as the integrator multiplies them",
            ["lights"] = lights,
            ["materials"] = materials,
            ["components"] = comps,
            ["files"] = new JsonObject
            {
                ["factors"] = "factors.npy: float32 [nnz], the factors of component c at entries offset .. offset + count - 1",
                ["pixels"] = "pixels.npy: int32 [nnz], the pixel (y * width + x) of each factor, ascending within a component",
                ["centre"] = "centre.npy: float32 [2K, H, W], light k's centre-ray diffuse (2k) and specular (2k+1) factor",
                ["ids"] = "ids.npy: float32 [3, H, W], object index + 1 (0 = background), lit mask, colour fallback (1: eq. 3 on the band values)",
            },
        };
    }

    static JsonArray Arr(ReadOnlySpan<float> v)
    {
        var a = new JsonArray();
        foreach (float x in v) a.Add((JsonNode)JsonValue.Create((double)x));
        return a;
    }

    /// <summary>Reads lights/ back into a transfer whose components refer to <paramref name="scene"/>'s materials by name.</summary>
    public static LightTransfer Read(string outDir, Scene scene)
    {
        var dir = Path.Combine(outDir, Folder);
        var jsonPath = Path.Combine(dir, "lights.json");
        if (!File.Exists(jsonPath))
            throw new InputException(outDir, "has no per-light outputs (lights/lights.json)", "render with --formats …,lights or \"output\": { \"light_groups\": true }");
        JsonObject json;
        try { json = JsonNode.Parse(File.ReadAllText(jsonPath))!.AsObject(); }
        catch (JsonException e) { throw new InputException($"{jsonPath}:{(e.LineNumber ?? 0) + 1}", $"broken JSON: {e.Message}", "the file is damaged: render the folder again"); }
        int width = (int)json["width"]!, height = (int)json["height"]!, bands = (int)json["bands"]!;
        int n = width * height;
        var materialIndex = scene.Materials.Select((m, i) => (m.Name, i)).ToDictionary(p => p.Name, p => p.i);
        int Mat(JsonNode? name) => name is null ? -1 : materialIndex.TryGetValue((string)name!, out int i) ? i
            : throw new InputException(jsonPath, $"names material '{(string?)name}' which the scene does not have", "relight the folder with the scene it was rendered from");
        var comps = json["components"]!.AsArray().Select(c => new TransferComponent(
            (int)c!["light"]!, TransferComponent.ParseLobe((string)c["lobe"]!), Mat(c["material"]),
            c["chain"]!.AsArray().Select(x => (Mat(x!["material"]), (string)x["weight"]! == "transmit")).ToArray())
        { Band = c["band"] is { } band ? Band((int)band) : -1 }).ToArray();
        int Band(int b) => b >= 1 && b <= bands ? b - 1
            : throw new InputException(jsonPath, $"names band {b}, the render has {bands}", "the file is damaged: render the folder again");

        float[] Load(string file, int[] expected)
        {
            var path = Path.Combine(dir, file);
            if (!File.Exists(path)) throw new InputException(outDir, $"misses {Folder}/{file}", "render again with the lights output");
            using var s = new FileStream(path, FileMode.Open, FileAccess.Read, FileShare.Read, bufferSize: 1);   // one read into the array
            var (shape, data) = NpyReader.Read(s, path);
            if (!shape.SequenceEqual(expected))
                throw new InputException(path, $"has shape ({string.Join(", ", shape)}), lights.json says ({string.Join(", ", expected)})", "the folder mixes two renders; render again");
            return data;
        }
        var nodes = json["components"]!.AsArray();
        long nnz = nodes.Sum(c => (long)(int)c!["count"]!);
        var f = Load("factors.npy", [(int)nnz]);
        int[] pix;
        {
            var path = Path.Combine(dir, "pixels.npy");
            if (!File.Exists(path)) throw new InputException(outDir, $"misses {Folder}/pixels.npy", "render again with the lights output");
            using var s = new FileStream(path, FileMode.Open, FileAccess.Read, FileShare.Read, bufferSize: 1);
            var (shape, data) = NpyInt32.Read(s, path);
            if (shape.Length != 1 || shape[0] != nnz) throw new InputException(path, $"holds {string.Join("×", shape)} entries, lights.json says {nnz}", "the folder mixes two renders; render again");
            pix = data;
        }
        foreach (int p in pix) if ((uint)p >= (uint)n) throw new InputException(Path.Combine(dir, "pixels.npy"), $"pixel {p} is outside the {width}×{height} image", "the light-transfer files are damaged: render the folder again");
        var offsets = nodes.Select(c => (Offset: (int)c!["offset"]!, Count: (int)c["count"]!)).ToArray();
        foreach (var (o, c) in offsets)
        {
            if (o < 0 || c < 0 || (long)o + c > nnz) throw new InputException(jsonPath, $"a component's entries {o}…{o + c - 1} lie outside the {nnz} stored", "the folder mixes two renders; render again");
            for (int j = o + 1; j < o + c; j++)
                if (pix[j] <= pix[j - 1]) throw new InputException(Path.Combine(dir, "pixels.npy"), $"entry {j}: pixels of a component must ascend", "render again");
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
            objectIds[i] = (int)ids[i] - 1; litMasks[i] = (uint)ids[n + i]; fallback[i] = ids[2 * n + i] != 0;
            idsKept &= objectIds[i] + 1 == ids[i] && litMasks[i] == ids[n + i] && (fallback[i] ? 1f : 0f) == ids[2 * n + i];
        }
        // … and the same factors.npy and pixels.npy when the components' entries follow each other in order.
        bool contiguous = true;
        for (int c = 0, at = 0; c < offsets.Length; at += offsets[c].Count, c++) contiguous &= offsets[c].Offset == at;
        bool canonical = idsKept && contiguous
            && Canonical(Path.Combine(dir, "factors.npy"), NpyWriter.Preamble([(int)nnz]), 4 * nnz)
            && Canonical(Path.Combine(dir, "pixels.npy"), NpyInt32.Preamble([(int)nnz]), 4 * nnz)
            && Canonical(Path.Combine(dir, "centre.npy"), NpyWriter.Preamble([2 * k, height, width]), 4L * centre.Length)
            && Canonical(Path.Combine(dir, "ids.npy"), NpyWriter.Preamble([3, height, width]), 4L * ids.Length);
        return new LightTransfer
        {
            Width = width,
            Height = height,
            Bands = bands,
            Grid = scene.Grid,
            Components = comps,
            Factors = offsets.Select(o => f.AsSpan(o.Offset, o.Count).ToArray()).ToArray(),
            Pixels = offsets.Select(o => pix.AsSpan(o.Offset, o.Count).ToArray()).ToArray(),
            Merged = nodes.Select(c => (int?)c!["merged_chains"] ?? 1).ToArray(),
            CentreDiffuse = Enumerable.Range(0, k).Select(i => centre.AsSpan(2 * i * n, n).ToArray()).ToArray(),
            CentreSpecular = Enumerable.Range(0, k).Select(i => centre.AsSpan((2 * i + 1) * n, n).ToArray()).ToArray(),
            ObjectIds = objectIds,
            LitMasks = litMasks,
            Fallback = fallback,
            Rays = new RayCounters(),
            StoredIn = canonical ? Path.GetFullPath(outDir) : null,
        };
    }
}
