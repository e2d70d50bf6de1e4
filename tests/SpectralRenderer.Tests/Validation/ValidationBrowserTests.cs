using System.Text.Json.Nodes;
using SpectralRenderer.Tests.Cli;
using SpectralRenderer.Tests.Imaging;
using SpectralRenderer.Tests.Relight;
using SpectralRenderer.Validation;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Validation;

/// <summary>
/// The validation report in a real browser (Debian's Chromium, headless, playwright-core from tests/browser as the viewer's
/// tests): report.html opens without a console or page error and without fetching anything, its summary lists every
/// case, and every case's section is there with its heading, its plot drawn and its points.
/// </summary>
[Trait("Category", "Browser")]
[Trait("Category", "Interop")]   // a real browser: not part of the fast core (README)
public class ValidationBrowserTests(ITestOutputHelper output)
{
    [SkippableFact]
    public void The_report_opens_without_errors_and_shows_every_case()
    {
        var script = Path.Combine(Path.GetDirectoryName(ViewerBrowserTests.Script())!, "report-check.mjs");
        var dir = Path.Combine(Reference.TempDir(), "validation");
        var (code, _, stderr) = CliRunner.Run("validate", "--quick", "--quiet", "-o", dir);
        Assert.True(code == 0, stderr);
        var (exit, stdout, err) = Tool.Run(Tool.Find("node")!, [script, Path.Combine(dir, "report.html")], timeoutMs: 120000);
        output.WriteLine(stdout.Length > 3000 ? stdout[..3000] + "…" : stdout);
        Assert.True(exit == 0, $"browser check failed ({exit}): {stdout} {err}");
        var r = JsonNode.Parse(stdout.Trim().Split('\n')[^1])!;
        Assert.Empty(r["errors"]!.AsArray());
        Assert.Empty(r["requests"]!.AsArray());
        var names = ValidationCases.All.Select(c => c.Name).ToList();
        Assert.Equal(names, r["summary"]!.AsArray().Select(s => (string)s!["name"]!));
        Assert.All(r["summary"]!.AsArray(), s => Assert.Equal("pass", (string)s!["result"]!));
        var sections = r["sections"]!.AsArray();
        Assert.Equal(names, sections.Select(s => (string)s!["id"]!));
        foreach (var s in sections)
        {
            Assert.True((bool)s!["visible"]!, (string)s["id"]!);
            Assert.Equal("pass", (string)s["result"]!);
            Assert.True((int)s["points"]! > 1, (string)s["id"]!);
            var plot = Assert.Single(s["plots"]!.AsArray());
            Assert.True((double)plot!["width"]! > 100 && (double)plot["height"]! > 50, $"{s["id"]}: plot not drawn");
            Assert.True((int)plot["lines"]! >= 1);
        }
    }
}
