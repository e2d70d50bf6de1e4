using SpectralRenderer.Cli;

namespace SpectralRenderer.Tests.Cli;

/// <summary>
/// Issue 42: the `camera` and `recover` usage lines left options out, and `spectral help render` printed the general help.
/// Every command's usage (the lines of its --help before the first blank line) names every option its argument parser
/// accepts, and `spectral help NAME` prints what `spectral NAME --help` prints.
/// </summary>
public class UsageLineTests
{
    public static TheoryData<string> Commands() => [.. CommandLine.Names];

    static (int Code, string Out) Run(params string[] args)
    {
        var stdout = new StringWriter();
        int code = CommandLine.Run(args, stdout, new StringWriter());
        return (code, stdout.ToString());
    }

    [Theory]
    [MemberData(nameof(Commands))]
    public void The_usage_names_every_option_the_command_accepts(string command)
    {
        var (code, help) = Run(command, "--help");
        Assert.Equal(0, code);
        var declared = Arguments.LastDeclared.Where(o => o != "--help").ToList();
        Assert.NotEmpty(declared);
        var usage = help.Replace("\r", "").Split("\n\n")[0];
        Assert.StartsWith($"usage: spectral {command}", usage);
        // The output folder's spellings are one option: -o in a usage line names --out and --output.
        string[] output = ["-o", "--out", "--output"];
        bool Named(string o) => (output.Contains(o) ? output : [o])
            .Any(name => System.Text.RegularExpressions.Regex.IsMatch(usage, $@"(^|[\s\[|(]){name}(?![\w-])"));
        var missing = declared.Where(o => !Named(o)).ToList();
        Assert.True(missing.Count == 0, $"spectral {command}: its usage does not name {string.Join(", ", missing)}:\n{usage}");
    }

    [Theory]
    [MemberData(nameof(Commands))]
    public void Help_NAME_is_NAME_help(string command)
    {
        var (code, help) = Run("help", command);
        Assert.Equal(0, code);
        Assert.Equal(Run(command, "--help").Out, help);
    }
}
