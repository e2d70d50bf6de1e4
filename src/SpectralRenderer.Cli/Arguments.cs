using System.Globalization;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Pipeline;

namespace SpectralRenderer.Cli;

/// <summary>
/// A command's arguments: positionals and --options. Each command declares its options
/// (flags take no value); anything else is bad usage, reported in one line with a hint.
/// </summary>
public sealed class Arguments
{
    readonly Dictionary<string, List<string>> _options = new(StringComparer.Ordinal);
    readonly HashSet<string> _flags = new(StringComparer.Ordinal);

    public List<string> Positionals { get; } = [];
    public string Command { get; }

    /// <summary>The options (values and flags) the last command run on this thread declared: what its help must list.</summary>
    public static IReadOnlyList<string> LastDeclared => t_declared ?? [];
    [ThreadStatic] static List<string>? t_declared;

    public Arguments(string command, IReadOnlyList<string> args, IEnumerable<string> valueOptions, IEnumerable<string> flagOptions,
        IReadOnlyDictionary<string, string>? aliases = null)
    {
        Command = command;
        var values = new HashSet<string>(valueOptions);
        var flags = new HashSet<string>(flagOptions) { "--help" };
        t_declared = [.. values, .. flags];
        for (int i = 0; i < args.Count; i++)
        {
            var a = args[i];
            if (aliases is not null && aliases.TryGetValue(a, out var full)) a = full;
            if (a.StartsWith("--") || (a.StartsWith('-') && a.Length == 2 && !char.IsDigit(a[1])))
            {
                string? inline = null;
                int eq = a.IndexOf('=');
                if (eq > 0) { inline = a[(eq + 1)..]; a = a[..eq]; }
                if (a == "-h") a = "--help";
                if (flags.Contains(a)) { _flags.Add(a); continue; }
                if (!values.Contains(a))
                    throw new InputException("command line", $"unknown option {MessageText.Quote(a)}",
                        InputException.DidYouMean(a, values.Concat(flags)) ?? $"see 'spectral {command} --help'");
                var v = inline
                    ?? (i + 1 < args.Count
                        ? args[++i]
                        : throw new InputException("command line", $"option {a} needs a value", $"see 'spectral {command} --help'"));
                if (!_options.TryGetValue(a, out var list)) _options[a] = list = [];
                list.Add(v);
            }
            else Positionals.Add(a);
        }
    }

    public bool Help => _flags.Contains("--help");
    public bool Flag(string name) => _flags.Contains(name);
    public string? Value(string name) => _options.TryGetValue(name, out var l) ? l[^1] : null;
    public IReadOnlyList<string> Values(string name) => _options.TryGetValue(name, out var l) ? l : [];

    /// <summary>The values given of these render options (<see cref="RenderOptions"/>), by option name, for its parser.</summary>
    public Dictionary<string, IReadOnlyList<string>> Given(IEnumerable<RenderOption> options) =>
        options.Where(o => _options.ContainsKey(o.Flag)).ToDictionary(o => o.Name, o => (IReadOnlyList<string>)_options[o.Flag]);

    public int? Int(string name, int min, int max)
    {
        var v = Value(name);
        if (v is null) return null;
        if (!int.TryParse(v, NumberStyles.Integer, CultureInfo.InvariantCulture, out int n) || n < min || n > max)
            throw new InputException(name, $"{MessageText.Quote(v)} is not a whole number in {min}–{max}",
                $"e.g. {name} {Math.Clamp(4, min, max)} (see 'spectral {Command} --help')");
        return n;
    }

    public double? Double(string name)
    {
        var v = Value(name);
        if (v is null) return null;
        if (!double.TryParse(v, NumberStyles.Float, CultureInfo.InvariantCulture, out double d) || !double.IsFinite(d))
            throw new InputException(name, $"{MessageText.Quote(v)} is not a finite number",
                $"e.g. {name} 0.5 (see 'spectral {Command} --help')");
        return d;
    }

    /// <summary>A finite number in (<paramref name="min"/>, <paramref name="max"/>] (<paramref name="unit"/> names what it is
    /// in).</summary>
    public double? Double(string name, double min, double max, string unit)
    {
        var v = Value(name);
        if (Double(name) is not { } d) return null;
        if (!(d > min && d <= max))
            throw new InputException(name,
                $"{MessageText.Quote(v)} is outside {min.ToString(CultureInfo.InvariantCulture)} (exclusive) to "
                    + $"{max.ToString("G3", CultureInfo.InvariantCulture)} {unit}",
                $"see 'spectral {Command} --help'");
        return d;
    }
}
