using System.Text;
using SharpFuzz;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Imaging;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Fuzz;

/// <summary>
/// One fuzz target per reader: bytes in, and the only acceptable failure is <see cref="InputException"/>
/// (one line for the user). Any other exception, a hang or a crash is a finding. Usage: Fuzz TARGET [FILE]
/// (with FILE: run once on it, for reproducing a finding; without: under afl-fuzz).
/// </summary>
public static class Program
{
    static readonly Dictionary<string, Action<byte[]>> Targets = new(StringComparer.Ordinal)
    {
        // A scene that names no file that exists: meshes and CSVs are looked up in a folder that is not there.
        ["scene"] = b => SceneLoader.Parse(b, "/nonexistent-fuzz/scene.json"),
        ["csv"] = b => CsvSpectrumReader.Parse(Encoding.UTF8.GetString(b), "fuzz.csv"),
        ["obj"] = b => ObjReader.Parse((ReadOnlySpan<byte>)b, "fuzz.obj"),
        ["ply"] = b => PlyReader.Parse(b, "fuzz.ply"),
        ["exr"] = b => ExrReader.Read(b, "fuzz.exr"),
        ["npy"] = b => NpyReader.Read(new MemoryStream(b), "fuzz.npy"),
        ["png"] = b => PngReader.Read(new MemoryStream(b), "fuzz.png"),
        ["ies"] = b => IesReader.Parse(Encoding.UTF8.GetString(b), "fuzz.ies").Table.Evaluate(10, 20),
        ["ldt"] = b => EulumdatReader.Parse(Encoding.UTF8.GetString(b), "fuzz.ldt").Table.Evaluate(10, 20),
        // An ENVI pair: the header text up to the first NUL byte, the samples after it.
        ["envi"] = b =>
        {
            int nul = Array.IndexOf(b, (byte)0);
            var header = EnviReader.ParseHeader(Encoding.UTF8.GetString(b, 0, nul < 0 ? b.Length : nul), "fuzz.hdr");
            EnviReader.ReadData(new MemoryStream(nul < 0 ? [] : b[(nul + 1)..]), header, "fuzz.img");
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
