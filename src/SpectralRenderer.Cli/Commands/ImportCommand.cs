using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes.Import;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral import FILE [-o scene.json]`: a Mitsuba 3, pbrt-v4 or glTF 2.0 scene converted to our scene JSON.</summary>
public static class ImportCommand
{
    const string Help = """
        usage: spectral import FILE [-o scene.json] [--lenient] [--models DIR]

        Converts a scene of another renderer (Mitsuba 3 XML, pbrt-v4, glTF 2.0) into our scene JSON
        (docs/scene-format.md; the conversions and their units in docs/import.md). With -o the JSON is
        written there, each mesh the importer made as binary PLY in SCENE-meshes/ beside it (meshes that
        were files already are referred to, not copied) and import-report.json beside it: every element
        approximated, ignored, uplifted or converted, with its file and line. Without -o the JSON (meshes
        inline) goes to standard output. A one-line summary goes to standard error. The same input gives
        the same bytes. `spectral render FILE` renders such a file directly (the same conversion).

          -o, --out FILE   the scene JSON to write (default: standard output)
          --lenient        report and skip elements without a counterpart (a medium, a hair BSDF)
                           instead of failing
          --models DIR     another folder to search for meshes (repeatable; after the file's own)
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a =
            new Arguments("import", argv, ["-o", "--out", "--models"], ["--lenient"], new Dictionary<string, string> { ["-o"] = "--out" });
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1)
            throw new InputException("command line",
                a.Positionals.Count == 0 ? "no scene file given" : $"unexpected argument {MessageText.Quote(a.Positionals[1])}",
                "usage: spectral import FILE [-o scene.json]");
        var source = a.Positionals[0];
        if (!File.Exists(source))
            throw new InputException(source, "no such file", "give the path of a .xml, .pbrt, .gltf or .glb scene")
            { Problem = InputProblem.MissingFile };
        var models = a.Values("--models");
        foreach (var folder in models)
            if (!Directory.Exists(folder))
                throw new InputException("--models", $"folder {MessageText.Quote(folder, 120)} does not exist", "give an existing folder");
        var imported = SceneFormats.Convert(source, new ImportOptions(a.Flag("--lenient"), models));
        if (a.Value("--out") is { } output)
        {
            if (string.IsNullOrWhiteSpace(output) || Directory.Exists(output))
                throw new InputException("-o", $"{MessageText.Quote(output)} is not a file name",
                    "give the scene JSON to write, e.g. -o scene.json");
            var dir = Path.GetDirectoryName(Path.GetFullPath(output))!;
            Directory.CreateDirectory(dir);
            ImportWriter.WriteFolder(imported, source, output);
        }
        else
        {
            stdout.Flush();
            var bytes = ImportWriter.InlineJson(imported);
            if (stdout == Console.Out)
            {
                using var raw = Console.OpenStandardOutput();
                raw.Write(bytes);
            }
            else stdout.Write(Encoding.UTF8.GetString(bytes));
        }
        stderr.WriteLine(MessageText.Line($"spectral import: {imported.Report.Summary()}"));
        return CommandLine.Success;
    }
}
