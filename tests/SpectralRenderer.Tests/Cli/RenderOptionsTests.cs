using System.Text.Json.Nodes;
using System.Text.RegularExpressions;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Output.Products;
using SpectralRenderer.Pipeline;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Tests.Cli;

/// <summary>
/// The one table of render options (issue 38): `spectral render --help` is generated from it and names every output
/// product; every option it defines is one the command takes; the C ABI's JSON spells each value as the command line does,
/// and a bad value gives the command line's one line whichever door it came through.
/// </summary>
public class RenderOptionsTests
{
    static string Help()
    {
        var (code, stdout, _) = CliRunner.Run("render", "--help");
        Assert.Equal(0, code);
        return stdout;
    }

    [Fact]
    public void The_help_names_every_output_format_of_the_product_table()
    {
        // The reference is the product table (the registration point of the formats), not the help's own text: the hand-written
        // help named ten of the eleven scene formats (grids was missing).
        var formats = Regex.Match(Help(), @"--formats LIST\s+(.*?)\n  --", RegexOptions.Singleline).Groups[1].Value;
        Assert.NotEmpty(formats);
        foreach (var p in OutputProductTable.All.Where(p => p.Flag != OutputProducts.None))
            Assert.Matches($@"\b{p.Name}\b", formats);
        Assert.Contains("grids", formats);
    }

    [Fact]
    public void Every_option_the_help_defines_is_taken_and_the_usage_line_names_each()
    {
        var help = Help();
        var defined = Regex.Matches(help, @"^\s+(?:-\w, )?--([a-z][a-z-]*)", RegexOptions.Multiline)
            .Select(m => m.Groups[1].Value).ToHashSet();
        var usage = help.Split("\n\n")[0];
        var named = Regex.Matches(usage, @"\[(?:-o|--([a-z][a-z-]*))")
            .Select(m => m.Groups[1].Success ? m.Groups[1].Value : "out").ToHashSet();
        Assert.Equal(defined.Order(), named.Order());
        // -o, the table's 18 options (issue 38 counted 19 spellings with -o, --out and --band-range; issue 42 added --exposure)
        // and --quiet, each taken: a missing scene is what fails.
        Assert.Equal(20, defined.Count);
        var missing = Path.Combine(Reference.TempDir(), "missing.json");
        foreach (var name in defined)
        {
            string[] args = name == "quiet" ? ["render", missing, "--quiet"] : ["render", missing, $"--{name}", "1"];
            var (code, _, err) = CliRunner.Run(args);
            Assert.Equal(2, code);
            Assert.DoesNotContain("unknown option", err);
        }
        Assert.Contains("unknown option '--nonesuch'", CliRunner.Run("render", missing, "--nonesuch", "1").Err);
    }

    [Fact]
    public void The_json_options_are_the_command_line_spellings()
    {
        var o = JsonNode.Parse("""
            { "width": 48, "target_error": 0.01, "crop": [0, 0, 8, 8], "formats": ["npy", "lights"],
              "models": ["a", "b c"], "exr_compression": "none", "shard": null }
            """)!.AsObject();
        var given = RenderOptions.FromJson(o);
        Assert.Equal(["crop", "exr-compression", "formats", "models", "target-error", "width"], given.Keys.Order());
        Assert.Equal(["48"], given["width"]);
        Assert.Equal(["0.01"], given["target-error"]);
        Assert.Equal(["0,0,8,8"], given["crop"]);
        Assert.Equal(["npy,lights"], given["formats"]);
        Assert.Equal(["a", "b c"], given["models"]);   // repeatable: each value its own, as --models a --models 'b c'
        Assert.Equal(["none"], given["exr-compression"]);
        var e = Assert.Throws<InputException>(() => RenderOptions.FromJson(JsonNode.Parse("""{"widht": 8}""")!.AsObject()));
        Assert.Equal("options.widht", e.Where);
        Assert.Contains("'width'", e.Hint);
        Assert.Throws<InputException>(() => RenderOptions.FromJson(JsonNode.Parse("""{"spp": true}""")!.AsObject()));
    }

    [Theory]
    [InlineData("spp", "0")]
    [InlineData("threads", "2000")]
    [InlineData("shards", "x")]
    [InlineData("target-error", "1.5")]
    [InlineData("bands", "0")]
    [InlineData("wave", "400:10:700")]
    public void A_bad_value_is_the_command_lines_line_through_the_json(string name, string value)
    {
        var scene = Path.Combine(Reference.TempDir(), "s.json");
        File.WriteAllText(scene, """{ "camera": { "width": 8, "height": 8 } }""");
        // The command line: "spectral render: WHERE: WHAT (hint: HINT)".
        string[] args = name == "wave"
            ? ["render", scene, "--wave", "400:10:700", "--bands", "1:2:3"]
            : ["render", scene, $"--{name}", value];
        var (code, _, err) = CliRunner.Run(args);
        Assert.Equal(2, code);
        // The C ABI's door: the JSON options through the same table.
        var json = name == "wave" ? """{"wave": "400:10:700", "bands": "1:2:3"}""" : $$"""{"{{name.Replace('-', '_')}}": "{{value}}"}""";
        var e = Assert.Throws<InputException>(() =>
            RenderOptions.Parse(RenderOptions.FromJson(JsonNode.Parse(json)!.AsObject()), () => File.ReadAllBytes(scene)));
        Assert.Equal(err.Trim(), "spectral render: " + MessageText.Escape(e.Message));
    }
}
