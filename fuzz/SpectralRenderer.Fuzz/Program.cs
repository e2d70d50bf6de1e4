using System.Text;
using SharpFuzz;
using SpectralRenderer.Analysis.Recovery;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Distributed;
using SpectralRenderer.Geometry;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Whitted;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Import;
using SpectralRenderer.Scenes.Import.Pbrt;
using SpectralRenderer.Scenes.Import.Gltf;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Sensor;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Fuzz;

/// <summary>
/// One fuzz target per reader: bytes in, and the only acceptable failure is <see cref="InputException"/>
/// (one line for the user). Any other exception, a hang or a crash is a finding. Usage: Fuzz TARGET [FILE]
/// (with FILE: run once on it, for reproducing a finding; without: under afl-fuzz).
/// </summary>
public static class Program
{
    /// <summary>A scratch folder of this process: the sweep target's base scene (good.json) beside the plan.</summary>
    static readonly Lazy<string> Work = new(() =>
    {
        var dir = Directory.CreateTempSubdirectory("spectral-fuzz-").FullName;
        File.WriteAllText(Path.Combine(dir, "good.json"), GoodScene);
        return dir;
    });

    static string Scratch(string name, byte[] bytes)
    {
        var path = Path.Combine(Work.Value, name);
        File.WriteAllBytes(path, bytes);
        return path;
    }

    const string GoodScene = """
        { "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 6 }, "bands": "400:700:4",
          "materials": { "green": { "diffuse": "colorchecker:14" }, "glass": { "diffuse": 0.1, "transmit": 0.8, "ior": 1.5 } },
          "lights": [ { "type": "point", "position": [0, 3, 3], "spectrum": "D65" }, { "type": "point", "position": [3, 3, 3], "spectrum": "A" } ],
          "objects": [ { "type": "sphere", "radius": 1, "material": "green" }, { "type": "sphere", "radius": 0.5, "center": [1, 0, 1], "material": "glass" } ] }
        """;

    static readonly Lazy<Scene> LightsScene =
        new(() => SceneLoader.Parse(Encoding.UTF8.GetBytes(GoodScene), "/nonexistent-fuzz/scene.json"));

    static readonly Dictionary<string, Action<byte[]>> Targets = new(StringComparer.Ordinal)
    {
        // A scene that names no file that exists: meshes and CSVs are looked up in a folder that is not there.
        ["scene"] = b => SceneLoader.Parse(b, "/nonexistent-fuzz/scene.json"),
        ["csv"] = b => CsvSpectrumReader.Parse(Encoding.UTF8.GetString(b), "fuzz.csv"),
        ["obj"] = b => ObjReader.Parse((ReadOnlySpan<byte>)b, "fuzz.obj"),
        ["ply"] = b => PlyReader.Parse(b, "fuzz.ply"),
        ["exr"] = b => ExrReader.Read(b, "fuzz.exr"),
        ["matrix"] = b => ReradiationExrReader.Read(b, "fuzz.exr"),   // a bispectral re-radiation matrix (Fichet et al. 2021)
        ["npy"] = b => NpyReader.Read(new MemoryStream(b), "fuzz.npy"),
        // A heterogeneous medium's density grid, Mitsuba .vol or NumPy .npy by its first bytes, placed and integrated along a ray.
        ["densitygrid"] = b =>
        {
            var s = DensityGridReader.Read(b, "fuzz.vol");
            var (min, max) = s.Bounds ?? (System.Numerics.Vector3.Zero, System.Numerics.Vector3.One);
            var grid = new DensityGrid(s.Data, s.Nx, s.Ny, s.Nz, min, max);
            grid.OpticalDepth(min - System.Numerics.Vector3.One, System.Numerics.Vector3.Normalize(new(1, 0.7f, 0.3f)), float.PositiveInfinity);
        },
        ["png"] = b => PngReader.Read(new MemoryStream(b), "fuzz.png"),
        ["jpeg"] = b => JpegReader.Read(b, "fuzz.jpg"),
        // High-dynamic-range environment maps: Radiance RGBE (.hdr) and PFM, the first byte choosing the reader.
        ["hdr"] = b =>
        {
            if (b.Length > 0 && b[0] == (byte)'P') PfmReader.Read(b, "fuzz.pfm");
            else RgbeReader.Read(b, "fuzz.hdr");
        },
        // A glTF 2.0 asset, .gltf JSON or .glb by its first bytes (files it names are looked up in the scratch folder), converted
        // and the scene loaded as `spectral render FILE.gltf` loads it.
        ["gltf"] = b =>
        {
            var path = Scratch("fuzz.gltf", b);
            SceneLoader.Parse(ImportWriter.InlineJson(new GltfFormat().Convert(path, new ImportOptions())), path);
        },
        ["ies"] = b => IesReader.Parse(Encoding.UTF8.GetString(b), "fuzz.ies").Table.Evaluate(10, 20),
        ["ldt"] = b => EulumdatReader.Parse(Encoding.UTF8.GetString(b), "fuzz.ldt").Table.Evaluate(10, 20),
        // Our own manifests, never trusted when read back (JsonFields): render.json, lights/lights.json (against a fixed
        // two-light scene), camera.json; a sweep plan (beside a fixed base scene, every job's scene checked) and a sensor file.
        ["manifest"] = b => RenderManifest.Parse(JsonFields.Parse(Encoding.UTF8.GetString(b), "render.json", "fuzz"), "render.json"),
        ["lights"] = b => WhittedTransferFiles.ParseLayout(JsonFields.Parse(Encoding.UTF8.GetString(b), "lights.json", "fuzz"), "lights.json",
            LightsScene.Value),
        ["camera"] = b => CameraCapture.Read(JsonFields.Parse(Encoding.UTF8.GetString(b), "camera.json", "fuzz"), "camera.json"),
        ["sweep"] = b =>
        {
            var plan = Scratch("plan.json", b);
            SweepPlan.Load(plan).CheckJobs(SweepPlan.Load(plan).Jobs.Take(64), new SceneOverrides(), Path.Combine(Work.Value, "out"));
        },
        ["sensor"] = b => SensorFile.Resolve(Scratch("sensor.json", b)),
        // A Mitsuba 3 XML scene converted (issue 39), and the converted JSON loaded as a render would load it.
        ["mitsuba"] = b =>
        {
            var xml = Scratch("scene.xml", b);
            var imported = SceneFormats.Convert(xml, new ImportOptions());
            SceneLoader.Parse(ImportWriter.InlineJson(imported), xml);
        },
        // An ENVI pair: the header text up to the first NUL byte, the samples after it.
        ["envi"] = b =>
        {
            int nul = Array.IndexOf(b, (byte)0);
            var header = EnviReader.ParseHeader(Encoding.UTF8.GetString(b, 0, nul < 0 ? b.Length : nul), "fuzz.hdr");
            EnviReader.ReadData(new MemoryStream(nul < 0 ? [] : b[(nul + 1)..]), header, "fuzz.img");
        },
        // A pbrt-v4 scene converted (includes and meshes looked up in a folder that is not there), then loaded.
        ["pbrt"] = b =>
        {
            const string path = "/nonexistent-fuzz/scene.pbrt";
            var scene = new PbrtConverter(path, new ImportOptions(Lenient: true)).ConvertText(Encoding.UTF8.GetString(b));
            SceneLoader.Parse(ImportWriter.InlineJson(scene), path);
        },
    };

    public static int Main(string[] args)
    {
        if (args.Length == 0 || !Targets.TryGetValue(args[0], out var target))
        {
            Console.Error.WriteLine($"usage: Fuzz {string.Join('|', Targets.Keys)} [FILE]");
            return 2;
        }
        if (args.Length > 1)
        {
            try { target(File.ReadAllBytes(args[1])); Console.WriteLine("accepted"); }
            catch (InputException e) { Console.WriteLine(e.Message); }
            return 0;
        }
        Fuzzer.Run(stream =>
        {
            var ms = new MemoryStream();
            stream.CopyTo(ms);
            try { target(ms.ToArray()); }
            catch (InputException) { /* bad input, reported as promised */ }
        });
        return 0;
    }
}
