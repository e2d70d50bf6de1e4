using System.Globalization;
using System.Text;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Output.Products;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Pipeline;

/// <summary>What an option's value is: a whole number, a finite number, a text (checked where it is used).</summary>
public enum RenderOptionKind { Integer, Number, Text }

/// <summary>
/// One option of a render: its <see cref="Name"/> (<c>--NAME</c> on the command line; <see cref="Key"/>, the name with
/// '_' for '-', in the C ABI's options JSON and as Python's keyword), its kind, the range of an integer
/// (<see cref="Min"/>…<see cref="Max"/>), the placeholder of its value and its help line in `spectral render --help`.
/// A repeatable option (<see cref="Repeatable"/>: --models) may be given several times; its values are kept in order.
/// </summary>
public sealed record RenderOption(string Name, RenderOptionKind Kind, string Value, string Help, int Min = int.MinValue,
    int Max = int.MaxValue, bool Repeatable = false)
{
    /// <summary>The command line's spelling, "--width".</summary>
    public string Flag => "--" + Name;
    /// <summary>The C ABI's JSON key and Python's keyword, "exr_compression".</summary>
    public string Key => Name.Replace('-', '_');
}

/// <summary>The checked values of a render's options: the scene's overrides, the integrator, threads, products, region.</summary>
/// <param name="Crop">--crop's text (X0,Y0,X1,Y1), checked against the film once the scene is loaded.</param>
/// <param name="Shard">--shard's text (I/N or none); with <paramref name="Shards"/> resolved by the shards' rule in the
/// layer above this one, which may read a job array's variables.</param>
public sealed record RenderOptionValues(SceneOverrides Overrides, string? Integrator, int Threads, IReadOnlyList<string> Products,
    string? Crop, string? Shard, int? Shards)
{
    /// <summary>The request these options make for <paramref name="scenePath"/> (its region already resolved).</summary>
    public RenderRequest Request(string scenePath, RenderRegion? region) => new()
    {
        ScenePath = scenePath,
        Overrides = Overrides,
        Products = Products,
        Integrator = Integrator,
        Region = region,
        Threads = Threads,
    };
}

/// <summary>
/// The one table of a render's options, read by `spectral render` (its argv and its --help, generated here), by
/// `spectral bench` (the options it shares), by libspectral's <c>spectral_render</c> (its options JSON) and so by Python's
/// <c>render(scene, **options)</c>. Each option is checked once, here, with the same one-line message whichever door it
/// came through; the bands rule (a bare count keeps the scene's range) is <see cref="Parse"/>'s. A new render option is
/// one row of <see cref="All"/> and its line in <see cref="Parse"/>.
/// </summary>
public static class RenderOptions
{
    /// <summary>Every option, in the order of `spectral render --help`.</summary>
    public static IReadOnlyList<RenderOption> All { get; } =
    [
        new("width", RenderOptionKind.Integer, "W",
            "image width in pixels (overrides the scene's camera); --width or --height alone keeps the camera's aspect ratio"),
        new("height", RenderOptionKind.Integer, "H", "image height in pixels"),
        new("bands", RenderOptionKind.Text, "N|S:E:N",
            "band count over the scene's range, or band edges start:end:count: 395:705:31 is 31 bands of 10 nm from 395 to 705 nm"),
        new("band-range", RenderOptionKind.Text, "S:E:N", "band edges start:end:count (the same as --bands S:E:N)"),
        new("wave", RenderOptionKind.Text, "S:STEP:E",
            "band centres in MATLAB/ISETCam colon notation, each STEP wide: 400:10:700 is the same 31 bands, centred on 400, "
            + "410, …, 700 nm"),
        new("spp", RenderOptionKind.Integer, "N", "samples per pixel (1 = pixel centre; more = stratified jitter)", 1, 65536),
        new("target-error", RenderOptionKind.Number, "E",
            "adaptive sampling: each pixel stops once the relative standard error of its mean luminance is at most E (e.g. "
            + "0.01), taking at most --spp samples (render.json: sampling)"),
        new("threads", RenderOptionKind.Integer, "N", "worker threads (default: all cores); output is identical for any N", 1, 1024),
        new("rgb", RenderOptionKind.Text, "MODE", "srgb (default) or paper (the paper's eq. 4, linear, clipped)"),
        new("exposure", RenderOptionKind.Text, "E|auto",
            "the preview's exposure, over the scene's output.exposure: a multiplier on XYZ, or auto (from the whole image; a "
            + "shard or crop needs a number: every shard the same, e.g. the one a small whole render chose, its render.json's "
            + "colour.exposure)"),
        new("integration", RenderOptionKind.Text, "S",
            "exact (default: band values and colour integrated on the full tables), weighted (band products, prefiltered "
            + "colour weights) or paper (eq. 3)"),
        new("formats", RenderOptionKind.Text, "LIST",
            "comma-separated from png,bands,exr,envi,npy,aov,lights,photometry,noise,grids, or all (every one but lights, "
            + "photometry, noise and grids, the default); lights = the per-light transfer in lights/ for 'relight' and 'view'; "
            + "photometry = luminance (cd/m²) and illuminance (lx) maps (physical radiometry); noise = each pixel's standard "
            + "error per band and of luminance (noise.npy, noise.img/.hdr, stderr.* channels in spectral.exr; needs spp >= 2); "
            + "grids = the illuminance (lx) on the scene's \"calculation_grids\" (grids/NAME.csv and .svg)"),
        new("exr-compression", RenderOptionKind.Text, "C",
            "zip (default: deflate the chunks whose samples repeat, store noisy ones), zip-all (deflate every chunk: smallest "
            + "file, slower) or none"),
        new("models", RenderOptionKind.Text, "DIR",
            "a folder to search for mesh files (after the scene's folder, before $SPECTRAL_MODELS); may be given more than once",
            Repeatable: true),
        new("crop", RenderOptionKind.Text, "X0,Y0,X1,Y1",
            "render only film columns X0…X1−1 and rows Y0…Y1−1: every file holds the crop (EXR data window inside the full "
            + "display window; \"crop\" in render.json)"),
        new("shard", RenderOptionKind.Text, "I/N",
            "render strip I (from 0) of N: whole 32-row tile strips, full width; `spectral merge` assembles the N folders into "
            + "the whole render, byte for byte. Without --shard, a job array task takes I and N from SLURM_ARRAY_TASK_ID/_MIN/"
            + "_MAX/_STEP (or _COUNT), JOB_COMPLETION_INDEX (Kubernetes, with --shards N) or AWS_BATCH_JOB_ARRAY_INDEX/_SIZE; "
            + "--shard none renders the whole film even there (the C ABI and Python read no job array variable)"),
        new("shards", RenderOptionKind.Integer, "N", "the shard count where the scheduler gives none (Kubernetes Indexed Jobs)",
            1, 1 << 20),
        new("integrator", RenderOptionKind.Text, "NAME",
            "the integrator by its registered name (default: whitted, the paper's eq. 2 with Whitted recursion; path: "
            + "unidirectional path tracing)"),
    ];

    /// <summary>The option named <paramref name="name"/> (its <see cref="RenderOption.Name"/>), or null.</summary>
    public static RenderOption? Find(string name) => All.FirstOrDefault(o => o.Name == name);

    /// <summary>
    /// The help of <paramref name="options"/> (the table's, or a command's share of it): per option "  --NAME VALUE" and its
    /// help line from <paramref name="column"/> on, wrapped at word breaks to at most <paramref name="width"/> columns.
    /// </summary>
    public static string HelpLines(IEnumerable<RenderOption> options, int column = 24, int width = 118)
    {
        var w = new StringBuilder();
        string pad = new(' ', column);
        foreach (var o in options)
        {
            string head = $"  {o.Flag} {o.Value}";
            if (head.Length >= column - 1) { w.Append(head).Append('\n'); head = ""; }
            string line = head.PadRight(column);
            bool empty = true;
            foreach (var word in o.Help.Split(' '))
            {
                if (!empty && line.Length + 1 + word.Length > width) { w.Append(line).Append('\n'); line = pad; empty = true; }
                line += (empty ? "" : " ") + word;
                empty = false;
            }
            w.Append(line).Append('\n');
        }
        return w.ToString();
    }

    /// <summary>
    /// The given options checked and made a render's values: <paramref name="given"/> maps an option's name to its values
    /// (the last one counts, all of a repeatable one), each as the command line would spell it. <paramref name="sceneText"/>
    /// is read only for a bare band count, which keeps the scene's range. Options are checked before the scene is read.
    /// </summary>
    public static RenderOptionValues Parse(IReadOnlyDictionary<string, IReadOnlyList<string>> given, Func<byte[]> sceneText)
    {
        foreach (var name in given.Keys)
            if (Find(name) is null) throw new ArgumentException($"'{name}' is not a render option", nameof(given));
        string? Text(string name) => given.TryGetValue(name, out var v) && v.Count > 0 ? v[^1] : null;
        int? Int(string name)
        {
            var o = Find(name)!;
            if (Text(name) is not { } v) return null;
            if (!int.TryParse(v, NumberStyles.Integer, CultureInfo.InvariantCulture, out int n) || n < o.Min || n > o.Max)
                throw new InputException(o.Flag, $"{MessageText.Quote(v)} is not a whole number in {o.Min}–{o.Max}",
                    $"e.g. {o.Flag} {Math.Clamp(4, o.Min, o.Max)} (see 'spectral render --help')");
            return n;
        }

        int? threads = Int("threads");
        string? range = Text("band-range");
        string? bands = range ?? Text("bands");
        string? wave = Text("wave");
        if (bands is not null && wave is not null)
            throw new InputException("--wave", "--wave and --bands both give the bands",
                "use one: --wave 400:10:700 (centres) or --bands 395:705:31 (edges)");
        if (bands is not null && !bands.Contains(':'))
        {
            if (!int.TryParse(bands, NumberStyles.Integer, CultureInfo.InvariantCulture, out int n))
                throw new InputException("--bands", $"{MessageText.Quote(bands)} is neither a band count nor a grid start:end:count",
                    "e.g. --bands 40, --bands 395:705:31 (edges) or --wave 400:10:700 (centres)");
            if (n < 1 || n > BandGrid.MaxBands)
                throw new InputException("--bands", $"band count {n} is outside 1–{BandGrid.MaxBands}",
                    $"e.g. --bands 40 (at most {BandGrid.MaxBands} bands)");
            // A count keeps the scene's range: peek at it without loading the scene twice.
            var grid = SceneRange(sceneText());
            bands = string.Create(CultureInfo.InvariantCulture, $"{grid.Start}:{grid.End}:{n}");
        }
        if (bands is not null) BandGrid.Parse(bands, range is not null ? "--band-range" : "--bands");   // under the option given
        var models = given.TryGetValue("models", out var m) ? m.ToList() : [];
        foreach (var folder in models)
            if (!Directory.Exists(folder))
                throw new InputException("--models", $"folder {MessageText.Quote(folder, 120)} does not exist",
                    "pass the folder that holds the mesh files");
        var overrides = new SceneOverrides
        {
            Width = Int("width"),
            Height = Int("height"),
            Bands = bands,
            Wave = wave,
            SamplesPerPixel = Int("spp"),
            TargetError = TargetError(Text("target-error")),
            Rgb = Text("rgb"),
            Exposure = Text("exposure") is { } x ? (OutputOptions.ParseExposure(x).Auto ? "auto" : x.Trim()) : null,
            Integration = Text("integration"),
            Formats = SplitFormats(Text("formats")).Formats,
            ExrCompression = Text("exr-compression"),
            ModelDirectories = models,
        };
        return new RenderOptionValues(overrides, Text("integrator"), threads ?? 0, SplitFormats(Text("formats")).Registered,
            Text("crop"), Text("shard"), Int("shards"));
    }

    /// <summary>
    /// The options of a JSON object (the C ABI's): each key an option's <see cref="RenderOption.Key"/>; a string is the
    /// command line's text, a number its JSON text, an array of a repeatable option its values, of another its items joined
    /// by ',' (crop [0, 0, 8, 8], formats ["npy", "lights"]). An unknown key is bad input under "options.KEY".
    /// </summary>
    public static Dictionary<string, IReadOnlyList<string>> FromJson(JsonObject options)
    {
        var given = new Dictionary<string, IReadOnlyList<string>>(StringComparer.Ordinal);
        foreach (var (key, value) in options)
        {
            var o = All.FirstOrDefault(x => x.Key == key)
                ?? throw new InputException($"options.{key}", "unknown option",
                    InputException.DidYouMean(key, All.Select(x => x.Key)) ?? $"known: {string.Join(", ", All.Select(x => x.Key))}");
            if (value is null) continue;   // null: not given (Python's None)
            string[] items = value is JsonArray a ? [.. a.Select(i => Scalar(i, key))] : [Scalar(value, key)];
            given[o.Name] = o.Repeatable ? items : [string.Join(',', items)];
        }
        return given;
    }

    static string Scalar(JsonNode? node, string key) => node switch
    {
        JsonValue v when v.TryGetValue(out string? s) => s,
        JsonValue v when v.GetValueKind() == JsonValueKind.Number => v.ToJsonString(),
        _ => throw new InputException($"options.{key}", $"{MessageText.Quote(node?.ToJsonString() ?? "null")} is not a text or a number",
            $"e.g. {key}=\"…\" as on the command line (see 'spectral render --help')"),
    };

    /// <summary>--target-error: a relative standard error in (0, 1).</summary>
    static double? TargetError(string? text)
    {
        if (text is null) return null;
        if (!double.TryParse(text, NumberStyles.Float, CultureInfo.InvariantCulture, out double e) || !double.IsFinite(e))
            throw new InputException("--target-error", $"{MessageText.Quote(text)} is not a finite number",
                "e.g. --target-error 0.5 (see 'spectral render --help')");
        if (!(e > 0 && e < 1))
            throw new InputException("--target-error",
                $"{e.ToString(CultureInfo.InvariantCulture)} is not a relative error between 0 and 1",
                "e.g. --target-error 0.01 (1 % standard error of each pixel's luminance)");
        return e;
    }

    /// <summary>
    /// The --formats list parted into the scene's own product names (null: none given, or only registered ones — the
    /// scene's formats then apply) and the names of products registered without a scene flag.
    /// </summary>
    static (string? Formats, string[] Registered) SplitFormats(string? formats)
    {
        if (formats is null) return (null, []);
        var extra = OutputProductTable.All.Where(p => p.Flag == OutputProducts.None).Select(p => p.Name).ToHashSet(StringComparer.Ordinal);
        var names = formats.Split(',', StringSplitOptions.TrimEntries);
        string[] registered = [.. names.Where(extra.Contains)];
        if (registered.Length == 0) return (formats, []);
        var own = names.Where(n => !extra.Contains(n)).ToArray();
        return (own.Length == 0 ? null : string.Join(',', own), registered);
    }

    /// <summary>The scene's band range for a bare band count; the loader reports a bad scene.</summary>
    static BandGrid SceneRange(byte[] sceneText)
    {
        try
        {
            var node = JsonNode.Parse(sceneText, documentOptions: new JsonDocumentOptions
            {
                CommentHandling = JsonCommentHandling.Skip,
                AllowTrailingCommas = true,
                AllowDuplicateProperties = false,   // a key twice: the loader reports it with its place (an object with one broke here)
            });
            if (node?["wave"]?.GetValue<string>() is { } w) return BandGrid.ParseWave(w);
            if (node?["bands"]?.GetValue<string>() is { } g) return BandGrid.Parse(g);
        }
        catch (Exception e) when (e is JsonException or InvalidOperationException or InputException) { /* the loader reports it */ }
        return BandGrid.Default;
    }
}
