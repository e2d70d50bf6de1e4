using SpectralRenderer.Tests.Architecture.Probe.ByUsing;

namespace SpectralRenderer.Tests.Architecture;

/// <summary>
/// The layers are one-way (ARCHITECTURE.md): each namespace may use only the namespaces its rule lists.
/// The graph is read from the compiled engine and CLI (<see cref="NamespaceDependencies"/>), so it holds
/// every reference the compiler resolved, by using directive or by fully qualified name, and from their source
/// (<see cref="SourceDependencies"/>, whose names are built from <see cref="Allowed"/>), which holds what the compiler
/// folds away (constants, enum values, nameof). Each layer has a deliberate back edge in LayerProbes.cs that must be reported.
/// </summary>
public class LayeringTests
{
    const string R = "SpectralRenderer.";

    /// <summary>The arrows: a layer → the layers it may use directly. A namespace inside a layer's (a.b.c in a.b) belongs to it unless
    /// listed itself.</summary>
    public static readonly IReadOnlyDictionary<string, string[]> Allowed = new Dictionary<string, string[]>(StringComparer.Ordinal)
    {
        [R + "Diagnostics"] = [],
        [R + "Spectra"] = ["Diagnostics"],
        [R + "Color"] = ["Spectra", "Diagnostics"],
        [R + "Geometry"] = ["Diagnostics"],
        [R + "Acceleration"] = ["Geometry", "Diagnostics"],
        [R + "Scenes"] = ["Spectra", "Color", "Geometry", "Diagnostics"],
        [R + "Scenes.Loading"] = ["Scenes", "Imaging", "Spectra", "Color", "Geometry", "Diagnostics"],
        [R + "Scenes.Import"] = ["Scenes", "Imaging", "Spectra", "Color", "Geometry", "Diagnostics"],
        // Rendering in wings: the film (the renderer, samplers, scene geometry, the integrator interface and its capabilities)
        // and around it eq. 2's terms, the emitters, Whitted, the path tracer, photometry and the registry of integrators.
        // Whitted and the path tracer never use each other; the film, the terms and the emitters use neither.
        [R + "Rendering"] = ["Scenes", "Acceleration", "Imaging", "Geometry", "Spectra", "Color", "Diagnostics"],
        [R + "Rendering.Terms"] = ["Rendering", "Scenes", "Geometry", "Spectra", "Color", "Diagnostics"],
        [R + "Rendering.Emitters"] = ["Rendering", "Scenes", "Geometry", "Spectra", "Color", "Diagnostics"],
        [R + "Rendering.Whitted"] = ["Rendering.Terms", "Rendering", "Scenes", "Acceleration", "Imaging", "Geometry", "Spectra", "Color",
            "Diagnostics"],
        [R + "Rendering.PathTracing"] = ["Rendering.Emitters", "Rendering", "Scenes", "Acceleration", "Imaging", "Geometry", "Spectra",
            "Color", "Diagnostics"],
        [R + "Rendering.Illumination"] = ["Rendering.Emitters", "Rendering", "Scenes", "Acceleration", "Geometry", "Spectra", "Color",
            "Diagnostics"],
        [R + "Rendering.Registry"] = ["Rendering.Whitted", "Rendering.PathTracing", "Rendering.Terms", "Rendering", "Scenes", "Spectra",
            "Diagnostics"],
        [R + "Imaging"] = ["Spectra", "Color", "Diagnostics"],
        [R + "Output"] = ["Rendering.Registry", "Rendering.Illumination", "Rendering", "Scenes", "Geometry", "Imaging", "Spectra", "Color",
            "Diagnostics"],
        [R + "Sensor"] = ["Imaging", "Spectra", "Color", "Diagnostics"],
        [R + "Analysis"] = ["Output", "Sensor", "Imaging", "Spectra", "Color", "Diagnostics"],
        [R + "Pipeline"] =
            ["Output", "Rendering.Registry", "Rendering", "Scenes.Import", "Scenes.Loading", "Scenes", "Imaging", "Geometry", "Spectra",
            "Color", "Diagnostics"],
        [R + "Relighting"] = ["Analysis", "Sensor", "Pipeline", "Output", "Rendering.Registry", "Rendering.Terms", "Rendering.Illumination",
            "Rendering", "Scenes.Loading", "Scenes", "Imaging", "Spectra", "Color", "Diagnostics"],
        [R + "Distributed"] = ["Pipeline", "Output", "Rendering.Registry", "Rendering", "Scenes.Loading", "Scenes", "Imaging", "Spectra",
            "Color", "Diagnostics"],
        // The validation cases: small scenes built through the loader, measured by the renderer's integrators and photometry
        // and by the camera model, judged against closed forms; never the pipeline, the outputs or the CLI.
        [R + "Validation"] = ["Sensor", "Rendering.Registry", "Rendering.Illumination", "Rendering", "Scenes.Loading", "Scenes",
            "Geometry", "Imaging", "Spectra", "Color", "Diagnostics"],
        [R + "Cli"] = ["*"],
        [R + "Native"] = ["Distributed", "Relighting", "Analysis", "Sensor", "Pipeline", "Output", "Rendering.Registry", "Rendering.Terms",
            "Rendering", "Scenes.Loading", "Scenes", "Imaging", "Spectra", "Color", "Diagnostics"],
    };

    /// <summary>The layer a namespace belongs to (its longest listed prefix), or null.</summary>
    public static string? LayerOf(string ns, IReadOnlyDictionary<string, string[]> rules) =>
        rules.Keys.Where(k => ns == k || ns.StartsWith(k + ".", StringComparison.Ordinal)).MaxBy(k => k.Length);

    /// <summary>Every edge of <paramref name="graph"/> the rules do not allow, and every namespace of ours without a layer.</summary>
    public static List<string> Violations(IReadOnlyDictionary<string, SortedSet<string>> graph, IReadOnlyDictionary<string, string[]> rules,
        string root = "SpectralRenderer")
    {
        var bad = new List<string>();
        foreach (var (from, targets) in graph.OrderBy(p => p.Key, StringComparer.Ordinal))
        {
            if (from != root && !from.StartsWith(root + ".", StringComparison.Ordinal)) continue;
            var layer = LayerOf(from, rules);
            if (layer is null) { bad.Add($"{from}: no layer (add it to LayeringTests.Allowed and ARCHITECTURE.md)"); continue; }
            var ok = rules[layer];
            foreach (var to in targets)
            {
                if (to != root && !to.StartsWith(root + ".", StringComparison.Ordinal)) continue;   // the base library
                var target = LayerOf(to, rules);
                if (target == layer) continue;
                string? targetShort = target is null ? null : target[(root.Length + 1)..];
                if (ok.Contains("*") || (targetShort is not null && ok.Contains(targetShort))) continue;
                bad.Add($"{from} → {to}: {layer[(root.Length + 1)..]} may use only "
                    + $"{(ok.Length == 0 ? "nothing of ours" : string.Join(", ", ok))}");
            }
        }
        return bad;
    }

    static Dictionary<string, SortedSet<string>> Graph()
    {
        var g = NamespaceDependencies.Read(typeof(global::SpectralRenderer.Scenes.Scene).Assembly.Location);
        foreach (var (k, v) in NamespaceDependencies.Read(typeof(global::SpectralRenderer.Cli.CommandLine).Assembly.Location)) g[k] = v;
        return g;
    }

    static Dictionary<string, SortedSet<string>> SourceGraph()
    {
        var d = new DirectoryInfo(AppContext.BaseDirectory);
        while (d is not null && !File.Exists(Path.Combine(d.FullName, "SpectralRenderer.sln"))) d = d.Parent;
        Assert.NotNull(d);
        var src = Path.Combine(d.FullName, "src");
        var files = Directory.EnumerateFiles(src, "*.cs", SearchOption.AllDirectories)
            .Where(f => !f.Contains($"{Path.DirectorySeparatorChar}obj{Path.DirectorySeparatorChar}")
                && !f.Contains($"{Path.DirectorySeparatorChar}bin{Path.DirectorySeparatorChar}"));
        return SourceDependencies.Read(files);
    }

    [Fact]
    public void The_engine_and_the_CLI_have_no_edge_against_the_arrows()
    {
        var bad = Violations(Graph(), Allowed).Select(b => "compiled: " + b)
            .Concat(Violations(SourceGraph(), Allowed).Select(b => "source: " + b)).ToList();
        Assert.True(bad.Count == 0, "edges against the arrows:\n" + string.Join("\n", bad));
    }

    [Fact]
    public void The_source_reader_sees_using_directives_qualified_names_and_constants()
    {
        // What the compiled graph cannot see: a constant and an enum value are folded into the IL.
        const string snippet = """
            using System.Text;
            using SpectralRenderer.Spectra;
            namespace SpectralRenderer.Imaging;
            // a comment naming Rendering.Renderer is no dependency
            static class Probe
            {
                public static int A => SpectralRenderer.Rendering.Renderer.TileSize;
                public static int B => (int)Scenes.OutputProducts.Png;
                public static int C => (int)global::SpectralRenderer.Output.RenderManifest.FileName.Length;
            }
            """;
        var graph = new Dictionary<string, SortedSet<string>>
        {
            ["SpectralRenderer.Imaging"] = new(SourceDependencies.Scan(snippet).Select(e => e.To), StringComparer.Ordinal),
        };
        Assert.Equal(["SpectralRenderer.Output.RenderManifest.FileName.Length", "SpectralRenderer.Rendering.Renderer.TileSize",
            "SpectralRenderer.Scenes.OutputProducts.Png", "SpectralRenderer.Spectra"], graph["SpectralRenderer.Imaging"]);
        var bad = Violations(graph, Allowed);
        Assert.Equal(3, bad.Count);
        Assert.Contains(bad,
            b => b.StartsWith("SpectralRenderer.Imaging → SpectralRenderer.Rendering.Renderer.TileSize", StringComparison.Ordinal));
        Assert.Contains(bad,
            b => b.StartsWith("SpectralRenderer.Imaging → SpectralRenderer.Scenes.OutputProducts.Png", StringComparison.Ordinal));
        Assert.Contains(bad,
            b => b.StartsWith("SpectralRenderer.Imaging → SpectralRenderer.Output.RenderManifest", StringComparison.Ordinal));
    }

    /// <summary>The name of namespace <paramref name="to"/> as written inside <paramref name="from"/>: relative to the namespace both are
    /// in.</summary>
    static string Relative(string to, string from)
    {
        string[] a = from.Split('.'), b = to.Split('.');
        int common = 0;
        while (common < a.Length && common < b.Length - 1 && a[common] == b[common]) common++;
        return string.Join('.', b[common..]);
    }

    [Fact]
    public void Every_edge_the_rules_forbid_is_reported_through_a_constant()
    {
        // For every layer and every layer its rule does not allow, a constant read by a relative name (as C# binds it
        // inside the layer's namespace) and by a global:: name: no layer is left out of the source pattern.
        int pairs = 0;
        foreach (var (from, ok) in Allowed)
        {
            if (ok.Contains("*")) continue;
            foreach (var to in Allowed.Keys)
            {
                string shortTo = to[R.Length..];
                if (to == from || ok.Contains(shortTo) || from.StartsWith(to + ".", StringComparison.Ordinal)) continue;
                string snippet = $$"""
                    namespace {{from}};
                    static class Probe
                    {
                        public const int A = {{Relative(to, from)}}.Limits.Constant;
                        public const int B = global::{{to}}.Limits.Other;
                    }
                    """;
                var graph = new Dictionary<string, SortedSet<string>>
                {
                    [from] = new(SourceDependencies.Scan(snippet).Select(e => e.To), StringComparer.Ordinal),
                };
                Assert.Equal([$"{to}.Limits.Constant", $"{to}.Limits.Other"], graph[from]);
                var bad = Violations(graph, Allowed);
                Assert.True(bad.Count == 2, $"{from} → {to}: expected two violations, got:\n{string.Join("\n", bad)}\n{snippet}");
                pairs++;
            }
        }
        Assert.True(pairs > 100, $"only {pairs} forbidden pairs");
    }

    [Fact]
    public void A_nested_layer_may_use_the_layer_around_it()
    {
        // Inside SpectralRenderer.Scenes.Loading the names of SpectralRenderer.Scenes need no qualification at all, so the
        // source reader could not see such an edge: the rules must allow it.
        foreach (var (layer, ok) in Allowed)
            foreach (var outer in Allowed.Keys.Where(k => layer.StartsWith(k + ".", StringComparison.Ordinal)))
                Assert.True(ok.Contains("*") || ok.Contains(outer[R.Length..]),
                    $"{layer} must be allowed to use {outer}, which encloses it");
    }

    const string Layers = "SpectralRenderer.Tests.Architecture.Probe.Layers";

    /// <summary>The back edges of LayerProbes.cs: each layer but Cli → a layer its rule forbids.</summary>
    static readonly (string From, string To)[] ProbeBackEdges =
    [
        ("Diagnostics", "Spectra"), ("Spectra", "Color"), ("Color", "Geometry"), ("Geometry", "Acceleration"),
        ("Acceleration", "Scenes"), ("Scenes", "Scenes.Loading"), ("Scenes.Loading", "Rendering"),
        ("Scenes.Import", "Scenes.Loading"), ("Rendering", "Output"),
        ("Imaging", "Sensor"), ("Sensor", "Output"), ("Output", "Pipeline"), ("Pipeline", "Analysis"),
        ("Analysis", "Relighting"), ("Relighting", "Distributed"), ("Distributed", "Cli"), ("Validation", "Cli"), ("Native", "Cli"),
        ("Rendering.Terms", "Rendering.Whitted"), ("Rendering.Emitters", "Rendering.PathTracing"),
        ("Rendering.Whitted", "Rendering.PathTracing"), ("Rendering.PathTracing", "Rendering.Whitted"),
        ("Rendering.Illumination", "Rendering.Registry"), ("Rendering.Registry", "Output"),
    ];

    [Fact]
    public void Every_layer_has_a_back_edge_probe_and_each_is_reported()
    {
        // The rule table re-rooted at the probes' namespace, the probes' source read as the engine's is, and the compiled
        // test assembly read as the engine is: the constants leave no trace in the IL, the source reader reports each.
        var rules = Allowed.ToDictionary(p => Layers + p.Key[(R.Length - 1)..], p => p.Value, StringComparer.Ordinal);
        var covered = ProbeBackEdges.SelectMany(e => new[] { e.From, e.To }).ToHashSet();
        Assert.True(Allowed.Keys.All(k => covered.Contains(k[R.Length..])), "every layer is in a probe edge");
        Assert.True(ProbeBackEdges.Select(e => e.From).Distinct().Count() == Allowed.Count - 1, "every layer but Cli has a back edge");

        var compiled = NamespaceDependencies.Read(typeof(LayeringTests).Assembly.Location)
            .Where(p => p.Key.StartsWith(Layers + ".", StringComparison.Ordinal)).ToDictionary(p => p.Key, p => p.Value);
        Assert.Equal(Allowed.Count, compiled.Count);
        Assert.Empty(Violations(compiled, rules, Layers));

        var source = SourceDependencies.Read([Repo.PathOf("tests", "SpectralRenderer.Tests", "Architecture", "LayerProbes.cs")], rules);
        var bad = Violations(source, rules, Layers);
        foreach (var (from, to) in ProbeBackEdges)
        {
            var edge = Assert.Single(bad, b => b.StartsWith($"{Layers}.{from} → {Layers}.{to}.", StringComparison.Ordinal));
            Assert.Contains($": {from} may use only ", edge);
        }
        Assert.Equal(ProbeBackEdges.Length, bad.Count);
    }

    [Fact]
    public void The_graph_holds_the_edges_the_layers_are_built_on()
    {
        // Not empty, and not blind to any kind of layer: each of these is a real use in the code.
        var graph = Graph();
        Assert.Contains(R + "Scenes", graph[R + "Rendering"]);       // the integrator reads the scene
        Assert.Contains(R + "Acceleration", graph[R + "Rendering"]); // through the BVH
        Assert.Contains(R + "Rendering", graph[R + "Rendering.Whitted"]);              // the wings stand on the film
        Assert.Contains(R + "Rendering.Terms", graph[R + "Rendering.Whitted"]);        // Whitted sums eq. 2's term tables
        Assert.Contains(R + "Rendering.Emitters", graph[R + "Rendering.PathTracing"]); // next-event estimation draws from the emitters
        Assert.Contains(R + "Rendering.PathTracing", graph[R + "Rendering.Registry"]); // the registry builds the integrators
        Assert.Contains(R + "Imaging", graph[R + "Output"]);         // the writers use the codecs
        Assert.Contains(R + "Output", graph[R + "Analysis"]);        // render folders are read through the manifest
        Assert.Contains(R + "Spectra", graph[R + "Color"]);
        Assert.Contains(R + "Cli.Paper", graph[R + "Cli.Commands"]);
        var source = SourceGraph();   // and the source reader sees the layers the old pattern left out
        Assert.Contains(source[R + "Analysis.Recovery"], to => to.StartsWith(R + "Sensor", StringComparison.Ordinal));
        Assert.Contains(source[R + "Cli.Commands"], to => to.StartsWith(R + "Relighting", StringComparison.Ordinal));
        Assert.Contains(source[R + "Cli.Commands"], to => to.StartsWith(R + "Distributed", StringComparison.Ordinal));
    }

    [Fact]
    public void A_back_edge_is_reported()
    {
        // The test of the test: the real graph plus one deliberate back edge (a codec reaching into the renderer).
        var graph = Graph();
        graph[R + "Imaging"].Add(R + "Rendering");
        var bad = Violations(graph, Allowed);
        var edge = Assert.Single(bad);
        Assert.StartsWith($"{R}Imaging → {R}Rendering: Imaging may use only Spectra, Color, Diagnostics", edge);
    }

    [Fact]
    public void The_reader_sees_fully_qualified_names_and_using_directives_alike()
    {
        // Probe.High uses Probe.ByUsing through a using directive and Probe.ByName only by a fully qualified name;
        // with rules that forbid both, both edges are reported from the compiled test assembly.
        var graph = NamespaceDependencies.Read(typeof(LayeringTests).Assembly.Location);
        const string P = "SpectralRenderer.Tests.Architecture.Probe";
        Assert.Contains($"{P}.ByUsing", graph[$"{P}.High"]);
        Assert.Contains($"{P}.ByName", graph[$"{P}.High"]);
        var rules = new Dictionary<string, string[]> { [$"{P}.High"] = [], [$"{P}.ByUsing"] = [], [$"{P}.ByName"] = [] };
        var probeGraph = graph.Where(p => rules.ContainsKey(p.Key)).ToDictionary(p => p.Key, p => p.Value);
        var bad = Violations(probeGraph, rules, P);
        Assert.Equal(2, bad.Count);
        Assert.Contains(bad, b => b.StartsWith($"{P}.High → {P}.ByUsing", StringComparison.Ordinal));
        Assert.Contains(bad, b => b.StartsWith($"{P}.High → {P}.ByName", StringComparison.Ordinal));
    }

    // The probe's High must see ByUsing through the using directive at the top of this file.
    internal static int ProbeUse() => Probe.High.Sum.Of(new Pair(1, 2));
}
