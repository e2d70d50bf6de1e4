using System.Numerics;
using System.Text;
using System.Text.Json.Nodes;
using System.Text.RegularExpressions;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Geometry;

namespace SpectralRenderer.Tests.FrontDoor;

/// <summary>
/// docs/scene-format.md is complete and its examples run. The keys the loader accepts are asked of the loader
/// itself: each object it reads is given an unknown key, and its error lists the keys allowed there ("allowed
/// here: …"); every one must be documented in the section of the docs for that object. A scan of the engine's
/// source checks that no Keys(...) context escapes the probe.
/// </summary>
public partial class SceneDocsTests
{
    const string Unknown = "zzzz_not_a_key";
    static string Docs => File.ReadAllText(Repo.PathOf("docs", "scene-format.md"));

    static JsonObject BaseScene() => JsonNode.Parse("""
        { "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 6 },
          "materials": { "m": { "diffuse": 0.5 } },
          "lights": [ { "type": "directional", "direction": [0, 0, -1], "spectrum": "D65" } ],
          "objects": [ { "type": "sphere", "material": "m" } ] }
        """)!.AsObject();

    /// <summary>Loads the scene after <paramref name="edit"/> and returns the loader's error.</summary>
    static InputException Fail(Action<JsonObject> edit, string dir)
    {
        var scene = BaseScene();
        edit(scene);
        var path = Path.Combine(dir, "probe.json");
        return Assert.Throws<InputException>(() => SceneLoader.Parse(Encoding.UTF8.GetBytes(scene.ToJsonString()), path));
    }

    static string[] Allowed(InputException e)
    {
        Assert.True(e.Hint is not null && e.Hint.StartsWith("allowed here: ", StringComparison.Ordinal),
            $"expected the list of allowed keys: {e.Message}");
        return e.Hint![14..].Split(", ");
    }

    static string[] Listed(string hint, string prefix) => hint[prefix.Length..].Split([", ", " or "], StringSplitOptions.TrimEntries);

    /// <summary>Every (docs section, key) the loader accepts, asked of the loader.</summary>
    static List<(string Section, string Context, string Key)> AcceptedKeys()
    {
        var dir = Reference.TempDir();
        File.WriteAllText(Path.Combine(dir, "tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        var keys = new List<(string, string, string)>();
        void Add(string section, string context, Action<JsonObject> edit)
        {
            foreach (var k in Allowed(Fail(edit, dir))) keys.Add((section, context, k));
        }
        JsonObject With(JsonObject o) { o[Unknown] = 1; return o; }

        Add("Top level", "$", s => s[Unknown] = 1);
        Add("camera", "$.camera", s => s["camera"]![Unknown] = 1);
        Add("output", "$.output", s => s["output"] = With([]));
        Add("Spectrum values", "spectrum object", s => s["lights"]![0]!["spectrum"] = With(new JsonObject { ["name"] = "D65" }));
        Add("Spectrum values", "rgb spectrum",
            s => s["lights"]![0]!["spectrum"] = With(new JsonObject { ["rgb"] = new JsonArray(1, 1, 1) }));
        Add("materials", "$.materials.m", s => s["materials"]!["m"]![Unknown] = 1);
        Add("materials", "$.materials.m.ior",
            s => s["materials"]!["m"]!["ior"] = With(new JsonObject { ["cauchy"] = new JsonArray(1.5, 0) }));
        Add("materials", "$.materials.m.ior.sellmeier",
            s => s["materials"]!["m"]!["ior"] = new JsonObject { ["sellmeier"] = With(new JsonObject { ["B1"] = 1 }) });
        Add("materials", "$.materials.m.diffuse (texture)",
            s => s["materials"]!["m"]!["diffuse"] = With(new JsonObject { ["texture"] = "t.png" }));
        Add("materials", "$.materials.m.diffuse.uv_transform",
            s => s["materials"]!["m"]!["diffuse"] = new JsonObject { ["texture"] = "t.png", ["uv_transform"] = With([]) });
        Add("materials", "$.materials.m.emission", s => s["materials"]!["m"]!["emission"] = With(new JsonObject { ["spectrum"] = "D65" }));
        Add("materials", "$.materials.m.fluorescence",
            s => s["materials"]!["m"] = new JsonObject { ["fluorescence"] = With(new JsonObject { ["matrix"] = "m.csv" }) });
        foreach (var model in new[] { "lambertian", "conductor", "plastic" })   // the built-in models (tests register others)
            Add("materials", $"material {model}", s => s["materials"]!["m"] = With(new JsonObject { ["type"] = model }));
        Add("materials", "$.materials.m.conductor", s => s["materials"]!["m"] = new JsonObject
        {
            ["type"] = "conductor",
            ["conductor"] = With(new JsonObject { ["n"] = 1, ["k"] = 1 }),
        });
        Add("Path tracing", "$.integrator", s => s["integrator"] = With(new JsonObject { ["type"] = "path" }));
        Add("Path tracing", "$.background", s => s["background"] = With(new JsonObject { ["spectrum"] = "D65", ["luminance"] = 1 }));
        Add("Path tracing", "$.sky", s => s["sky"] = With(new JsonObject { ["type"] = "daylight" }));
        Add("Path tracing", "$.sky envmap", s => s["sky"] = With(new JsonObject { ["type"] = "envmap" }));
        Add("Radiometry", "$.calculation_grids[0]", s =>
        {
            s["radiometry"] = "physical";
            s["calculation_grids"] = new JsonArray(With([]));
        });

        var lightTypes = Fail(s => s["lights"]![0]!["type"] = Unknown, dir);
        Assert.StartsWith("use ", lightTypes.Hint);
        foreach (var type in Listed(lightTypes.Hint!, "use "))
            Add("lights", $"light {type}", s => s["lights"]![0] = With(new JsonObject { ["type"] = type }));

        var objectTypes = Fail(s => s["objects"]![0]!["type"] = Unknown, dir);
        Assert.StartsWith("types: ", objectTypes.Hint);
        foreach (var type in Listed(objectTypes.Hint!, "types: "))
            Add("objects", $"object {type}", s => s["objects"]![0] = With(new JsonObject { ["type"] = type }));
        Add("objects", "transform", s => s["objects"]![0]!["transform"] = With([]));
        Add("objects", "$.medium", s => s["medium"] = With(new JsonObject { ["sigma_a"] = 1 }));
        Add("objects", "$.medium.phase", s => s["medium"] = new JsonObject
        {
            ["sigma_s"] = 1,
            ["phase"] = With(new JsonObject { ["type"] = "hg" }),
        });
        Add("objects", "mesh fit", s => s["objects"]![0] = new JsonObject
        {
            ["type"] = "mesh",
            ["file"] = "tri.obj",
            ["material"] = "m",
            ["fit"] = With(new JsonObject { ["min"] = new JsonArray(0, 0, 0), ["max"] = new JsonArray(1, 1, 1) }),
        });
        Add("objects", "mesh inline", s => s["objects"]![0] = new JsonObject
        {
            ["type"] = "mesh",
            ["material"] = "m",
            ["inline"] =
                With(new JsonObject { ["positions"] = new JsonArray(0, 0, 0, 1, 0, 0, 0, 1, 0), ["indices"] = new JsonArray(0, 1, 2) }),
        });
        return keys;
    }

    /// <summary>The text of the section "## NAME" of the docs, up to the next "## " heading.</summary>
    static string Section(string docs, string name)
    {
        var m = Regex.Match(docs, $@"^## {Regex.Escape(name)}\s*$(.*?)(?=^## |\z)", RegexOptions.Multiline | RegexOptions.Singleline);
        Assert.True(m.Success, $"docs/scene-format.md has no section '## {name}'");
        return m.Groups[1].Value;
    }

    [Fact]
    public void Every_key_the_loader_accepts_is_documented_in_its_section()
    {
        var docs = Docs;
        var keys = AcceptedKeys();
        Assert.True(keys.Count > 60, $"only {keys.Count} keys found: the probe lost its way");
        // Documented = named in code in that section: `key`, or "key" inside a code span such as { "min": … }.
        var missing = keys.Where(k =>
        {
            var text = Section(docs, k.Section);
            return !text.Contains($"`{k.Key}`", StringComparison.Ordinal) && !text.Contains($"\"{k.Key}\"", StringComparison.Ordinal);
        }).Select(k => $"{k.Context}: {k.Key} (section '{k.Section}')").Distinct().ToList();
        Assert.True(missing.Count == 0, "accepted by the loader but not in docs/scene-format.md:\n" + string.Join("\n", missing));
    }

    [GeneratedRegex(@"(?<!void )\bKeys\(\s*\w+\s*,")]
    private static partial Regex KeysCall();

    [Fact]
    public void The_probe_reaches_every_place_the_loader_checks_keys()
    {
        // Each call of the loader's Keys(element, path, allowed…) is one kind of JSON object; the probe above
        // asks all twenty-six (the light, object and material calls cover every type, the registered shape types' call
        // every registered shape: disk, cylinder; an rgb spectrum; an inline mesh; both kinds of sky, the daylight and the
        // environment map; a medium, the built-in homogeneous type's keys, and its phase function's). A new one must join the probe.
        var sources = Directory.GetFiles(Repo.PathOf("src", "SpectralRenderer"), "*.cs", SearchOption.AllDirectories)
            .Where(f => !f.Contains($"{Path.DirectorySeparatorChar}obj{Path.DirectorySeparatorChar}", StringComparison.Ordinal));
        var calls = sources.SelectMany(f => KeysCall().Matches(File.ReadAllText(f)).Select(m => $"{Path.GetFileName(f)}: {m.Value}"))
            .ToList();
        Assert.True(calls.Count == 26,
            $"{calls.Count} Keys(...) calls, the probe knows 26; add the new one to AcceptedKeys:\n" + string.Join("\n", calls));
    }

    // ---- the examples -------------------------------------------------------------------------------

    public static TheoryData<string, int> Examples()
    {
        var data = new TheoryData<string, int>();
        foreach (var file in new[] { "README.md", Path.Combine("docs", "scene-format.md") })
            for (int i = 0; i < ExampleBlocks(File.ReadAllText(Repo.PathOf(file))).Count; i++) data.Add(file, i);
        return data;
    }

    static List<string> ExampleBlocks(string markdown) =>
        Regex.Matches(markdown, @"^```json\s*\n(.*?)^```", RegexOptions.Multiline | RegexOptions.Singleline).Select(m => m.Groups[1].Value)
            .ToList();

    [Fact]
    public void The_docs_have_examples_to_run() => Assert.True(Examples().Count >= 2);

    [SkippableTheory]
    [MemberData(nameof(Examples))]
    public void Every_json_example_in_the_docs_renders_a_visible_subject(string file, int index)
    {
        var json = ExampleBlocks(File.ReadAllText(Repo.PathOf(file)))[index];
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "example.json");
        File.WriteAllText(scene, json);
        List<string> args =
            ["render", scene, "-o", Path.Combine(dir, "out"), "--width", "96", "--spp", "1", "--formats", "png,aov", "--quiet"];
        foreach (Match m in Regex.Matches(json, "\"file\"\\s*:\\s*\"([^\"]+)\""))
        {
            var mesh = ModelFiles.Require(m.Groups[1].Value);
            args.AddRange(["--models", Path.GetDirectoryName(mesh)!]);
        }
        var (code, _, err) = CliRunner.Run([.. args]);
        Assert.True(code == 0, $"{file} example {index + 1}: {err}");

        // The subject: every pixel that sees an object (object-id ≠ 0); its mean 8-bit sRGB level.
        var preview = PngReader.Read(Path.Combine(dir, "out", "preview.png"));
        var ids = PngReader.Read(Path.Combine(dir, "out", "object-id.png"));
        double sum = 0;
        long count = 0;
        for (int p = 0; p < ids.Width * ids.Height; p++)
        {
            if (ids.Samples[p] == 0) continue;
            sum += (preview.Samples[3 * p] + preview.Samples[3 * p + 1] + preview.Samples[3 * p + 2]) / 3.0;
            count++;
        }
        Assert.True(count > ids.Width * ids.Height / 10, $"{file} example {index + 1}: objects cover only {count} pixels");
        Assert.True(sum / count >= 40,
            $"{file} example {index + 1}: the subject's mean 8-bit level is {sum / count:F1}, below 40 (too dark to show anything)");
    }

    // ---- fit and transform ---------------------------------------------------------------------------

    [Fact]
    public void A_rotated_mesh_stays_in_its_fit_box_and_translate_with_fit_is_refused()
    {
        var dir = Reference.TempDir();
        // A tetrahedron 4 long in x, 1 in y and z. Turned 90° about z it is 4 tall; fitted into the 2 × 2 × 2 box
        // on the floor, the scale is min(2/1, 2/4, 2/1) = 0.5: 0.5 × 2 × 0.5, centred in x and z.
        File.WriteAllText(Path.Combine(dir, "long.obj"), "v 0 0 0\nv 4 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
        string Scene(string transform) => $$"""
            { "camera": { "position": [0, 1, 6], "look_at": [0, 1, 0], "width": 8, "height": 6 },
              "objects": [ { "type": "mesh", "file": "long.obj", "material": 0.5, "shading": "flat",
                             "transform": {{transform}}, "fit": { "min": [-1, 0, -1], "max": [1, 2, 1] } } ] }
            """;
        var s = SceneLoader.Parse(Encoding.UTF8.GetBytes(Scene("{ \"rotate\": [0, 0, 90] }")), Path.Combine(dir, "scene.json"));
        var b = s.Objects.Single().Mesh!.Bounds;
        AssertNear(new Vector3(-0.25f, 0, -0.25f), b.Min);
        AssertNear(new Vector3(0.25f, 2, 0.25f), b.Max);

        var e = Assert.Throws<InputException>(() =>
            SceneLoader.Parse(Encoding.UTF8.GetBytes(Scene("{ \"translate\": [1, 0, 0] }")), Path.Combine(dir, "scene.json")));
        Assert.Contains("$.objects[0].transform.translate: has no effect with fit", e.Message);
        Assert.Contains("move fit.min and fit.max", e.Message);
    }

    static void AssertNear(Vector3 expected, Vector3 actual)
    {
        Assert.True(Vector3.Distance(expected, actual) < 1e-5f, $"expected {expected}, got {actual}");
    }
}
