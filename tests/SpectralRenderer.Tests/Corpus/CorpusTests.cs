using System.Runtime.InteropServices;
using System.Text.Json;
using System.Text.Json.Nodes;
using System.Text.RegularExpressions;
using SpectralRenderer.Tests.Cli;

namespace SpectralRenderer.Tests.Corpus;

/// <summary>
/// The committed corpus of broken inputs and faults (tests/corpus, written by generate.py): every case runs
/// through the real CLI in-process and must end with its exit code and one printable line matching its pattern;
/// bad input (exit 2) must name the file (or option) and the place in it and carry a hint; a failed render
/// leaves nothing in its output folder.
/// </summary>
public class CorpusTests
{
    public static readonly string Root = FindRoot();
    static readonly string Inputs = Path.Combine(Root, "inputs");

    static string FindRoot()
    {
        for (var d = new DirectoryInfo(AppContext.BaseDirectory); d is not null; d = d.Parent)
        {
            var c = Path.Combine(d.FullName, "tests", "corpus");
            if (File.Exists(Path.Combine(c, "cases.json"))) return c;
        }
        throw new InvalidOperationException("tests/corpus/cases.json not found above " + AppContext.BaseDirectory);
    }

    public sealed record Case(string Name, string[] Args, string[] Setup, int Exit, string Stderr, string? File, string? Place)
    {
        public override string ToString() => Name;
    }

    static readonly Lazy<Case[]> All = new(() =>
    {
        var doc = JsonNode.Parse(System.IO.File.ReadAllText(Path.Combine(Root, "cases.json")))!.AsArray();
        return doc.Select(n => new Case((string)n!["name"]!, n["args"]!.AsArray().Select(a => (string)a!).ToArray(),
            n["setup"]!.AsArray().Select(a => (string)a!).ToArray(), (int)n["exit"]!, (string)n["stderr"]!,
            (string?)n["file"], (string?)n["place"])).ToArray();
    });

    public static TheoryData<string> Names()
    {
        var d = new TheoryData<string>();
        foreach (var c in All.Value) d.Add(c.Name);
        return d;
    }

    [Fact]
    public void The_corpus_holds_at_least_300_cases_with_unique_names()
    {
        Assert.True(All.Value.Length >= 300, $"{All.Value.Length} cases");
        Assert.Equal(All.Value.Length, All.Value.Select(c => c.Name).Distinct().Count());
        Assert.True(All.Value.Count(c => c.Exit == 2) >= 300);
    }

    static readonly Regex Hint = new(@"\(hint: [^)]{3,}", RegexOptions.CultureInvariant);

    [SkippableTheory]
    [MemberData(nameof(Names))]
    public void Case_ends_as_promised(string name)
    {
        var c = All.Value.Single(x => x.Name == name);
        var tmp = Reference.TempDir();
        string Sub(string s) => s.Replace("{in}", Inputs).Replace("{tmp}", tmp);
        foreach (var step in c.Setup) Setup(Sub(step), tmp);

        var (code, _, err) = CliRunner.Run(c.Args.Select(Sub).ToArray());
        var line = err.TrimEnd('\n');
        if (Environment.GetEnvironmentVariable("SPECTRAL_CORPUS_DUMP") is { Length: > 0 } dump)
            lock (All) System.IO.File.AppendAllText(dump, $"{c.Name}\t{code}\t{line}\n");
        Assert.True(code == c.Exit, $"exit {code}, expected {c.Exit}: {line}");
        Assert.DoesNotContain('\n', line);
        Assert.True(line.Length <= 330, $"{line.Length} characters: {line}");
        Assert.True(line.All(ch => ch >= ' ' && ch != '\x7f'), $"unprintable character in: {line}");
        Assert.DoesNotContain("internal error", line);
        Assert.True(Regex.IsMatch(line, c.Stderr, RegexOptions.CultureInvariant), $"/{c.Stderr}/ does not match: {line}");
        if (c.Exit == 2 && c.File is not null)
        {
            var named = Sub(c.File);
            if (Path.IsPathRooted(named)) named = Path.GetFileName(named.TrimEnd('/'));
            Assert.True(line.Contains(named, StringComparison.Ordinal), $"'{named}' is not named in: {line}");
            Assert.True(Regex.IsMatch(line, c.Place!, RegexOptions.CultureInvariant), $"no place /{c.Place}/ in: {line}");
            Assert.True(Hint.IsMatch(line), $"no hint in: {line}");
        }
        // A render that failed left nothing behind in its output folder.
        var outDir = Path.Combine(tmp, "out");
        if (code != 0 && Directory.Exists(outDir))
            Assert.Empty(Directory.EnumerateFileSystemEntries(outDir));
    }

    [DllImport("libc", SetLastError = true)]
    static extern int mkfifo(string path, uint mode);

    static readonly Lazy<string> BaseRender = new(() =>
    {
        var dir = Path.Combine(Reference.TempDir(), "base");
        var (code, _, err) = CliRunner.Run("render", Path.Combine(Inputs, "good.json"), "-o", dir, "--quiet");
        if (code != 0) throw new InvalidOperationException("the base render failed: " + err);
        return dir;
    });

    /// <summary>Set-up runs (<paramref name="runs"/>: good.json rendered, a camera run) into a folder of their own, made once and copied
    /// per case.</summary>
    static Lazy<string> Cached(params string[][] runs) => new(() =>
    {
        var dir = Reference.TempDir();
        foreach (var run in runs)
        {
            var (code, _, err) = CliRunner.Run(run.Select(a => a.Replace("{in}", Inputs).Replace("{dir}", dir)).ToArray());
            if (code != 0) throw new InvalidOperationException($"the set-up run {string.Join(' ', run)} failed: {err}");
        }
        return dir;
    });

    static readonly Lazy<string> LightsRender =
        Cached(["render", "{in}/good.json", "-o", "{dir}/r", "--formats", "npy,aov,lights", "--quiet"]);
    static readonly Lazy<string> CameraRun = Cached(["render", "{in}/good.json", "-o", "{dir}/r", "--formats", "npy,aov", "--quiet"],
        ["camera", "{dir}/r", "--sensor", "isetcam", "--noise", "off", "-o", "{dir}/cam"]);
    static readonly Lazy<string> Shards = Cached(
        ["render", "{in}/good.json", "--width", "8", "--height", "64", "--formats", "npy,aov", "--shard", "0/2", "-o", "{dir}/a",
            "--quiet"],
        ["render", "{in}/good.json", "--width", "8", "--height", "64", "--formats", "npy,aov", "--shard", "1/2", "-o", "{dir}/b",
            "--quiet"]);
    static readonly Lazy<string> Crop = Cached(["render", "{in}/good.json", "--crop", "0,0,4,3", "-o", "{dir}/r", "--quiet"]);

    static void Setup(string step, string tmp)
    {
        var w = step.Split(' ', 2);
        string P(string p) => Path.IsPathRooted(p) ? p : Path.Combine(tmp, p);
        switch (w[0])
        {
            case "mkdir": Directory.CreateDirectory(P(w[1])); break;
            case "touch": System.IO.File.WriteAllBytes(P(w[1]), []); break;
            case "chmod-ro":
                Skip.If(Environment.UserName == "root" || geteuid() == 0, "permissions do not bind root");
                if (!OperatingSystem.IsWindows()) System.IO.File.SetUnixFileMode(P(w[1]), UnixFileMode.UserRead | UnixFileMode.UserExecute);
                break;
            case "mkfifo":
                Assert.Equal(0, mkfifo(P(w[1]), Convert.ToUInt32("644", 8)));
                break;
            case "symlink":
                {
                    var a = w[1].Split(' ');
                    System.IO.File.CreateSymbolicLink(P(a[0]), a[1]);
                    break;
                }
            case "copy":
                {
                    var a = w[1].Split(' ');
                    System.IO.File.Copy(P(a[0]), P(a[1]), overwrite: true);
                    break;
                }
            case "remove":
                if (System.IO.File.Exists(P(w[1]))) System.IO.File.Delete(P(w[1]));
                break;
            case "base-render":
                CopyFolder(BaseRender.Value, P(w[1]));
                break;
            case "base-lights": CopyFolder(Path.Combine(LightsRender.Value, "r"), P(w[1])); break;
            case "base-crop": CopyFolder(Path.Combine(Crop.Value, "r"), P(w[1])); break;
            case "base-camera":
                foreach (var sub in new[] { "r", "cam" }) CopyFolder(Path.Combine(CameraRun.Value, sub), Path.Combine(P(w[1]), sub));
                break;
            case "base-shards":
                foreach (var sub in new[] { "a", "b" }) CopyFolder(Path.Combine(Shards.Value, sub), Path.Combine(P(w[1]), sub));
                break;
            case "json-del":
                {
                    var a = w[1].Split(' ', 2);
                    var file = P(a[0]);
                    var root = JsonNode.Parse(System.IO.File.ReadAllText(file))!;
                    var keys = a[1].Split('.');
                    JsonNode node = root;
                    foreach (var k in keys[..^1]) node = int.TryParse(k, out int i) ? node[i]! : node[k]!;
                    node.AsObject().Remove(keys[^1]);
                    System.IO.File.WriteAllText(file, root.ToJsonString());
                    break;
                }
            case "json-set":
                {
                    var a = w[1].Split(' ', 3);
                    var file = P(a[0]);
                    var root = JsonNode.Parse(System.IO.File.ReadAllText(file))!;
                    var keys = a[1].Split('.');
                    JsonNode node = root;
                    foreach (var k in keys[..^1]) node = int.TryParse(k, out int i) ? node[i]! : node[k]!;
                    var value = JsonNode.Parse(a[2]);
                    if (int.TryParse(keys[^1], out int last)) node.AsArray()[last] = value;
                    else node.AsObject()[keys[^1]] = value;
                    System.IO.File.WriteAllText(file, root.ToJsonString());
                    break;
                }
            default: throw new InvalidOperationException("unknown set-up step " + step);
        }
    }

    [DllImport("libc")]
    static extern uint geteuid();

    static void CopyFolder(string from, string to)
    {
        Directory.CreateDirectory(to);
        foreach (var f in Directory.GetFiles(from)) System.IO.File.Copy(f, Path.Combine(to, Path.GetFileName(f)));
        foreach (var d in Directory.GetDirectories(from)) CopyFolder(d, Path.Combine(to, Path.GetFileName(d)));
    }
}
