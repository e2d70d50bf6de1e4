using System.Globalization;
using SpectralRenderer.Cli;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Cli;

/// <summary>
/// ARCHITECTURE.md, "Extending", a command: a handler and one <see cref="CommandLine.Register"/> call from this assembly;
/// `spectral NAME …` then dispatches to it, lists it in --help and turns its bad input into the one-line message and exit 2.
/// </summary>
public class RegisteredCommandTests
{
    /// <summary>The example command: `spectral test-band-centres START:END:COUNT` prints each band's centre in nm, one a line.</summary>
    const string Name = "test-band-centres";

    static int BandCentres(string[] args, TextWriter stdout, TextWriter stderr)
    {
        if (args.Length != 1) { stderr.WriteLine($"usage: spectral {Name} START:END:COUNT"); return CommandLine.BadInput; }
        var grid = BandGrid.Parse(args[0]);
        for (int b = 0; b < grid.Count; b++) stdout.WriteLine(grid.Centre(b).ToString("0.###", CultureInfo.InvariantCulture));
        return CommandLine.Success;
    }

    static RegisteredCommandTests() =>
        CommandLine.Register(Name, "the centres of the bands START:END:COUNT, one a line (a test's example command)", BandCentres);

    [Fact]
    public void A_command_registered_from_outside_the_CLI_is_dispatched_listed_and_its_errors_handled()
    {
        // 400–700 nm in 3 bands of 100 nm: centres 450, 550, 650.
        var (code, stdout, stderr) = CliRunner.Run(Name, "400:700:3");
        Assert.True(code == CommandLine.Success, stderr);
        Assert.Equal("450\n550\n650\n", stdout.ReplaceLineEndings("\n"));

        (code, stdout, _) = CliRunner.Run("--help");
        Assert.Equal(CommandLine.Success, code);
        Assert.Contains($"  {Name} the centres of the bands", stdout);
        Assert.Contains(Name, CommandLine.Names);

        // Bad input thrown inside the command: CommandLine's one line, prefixed with the command's name, exit 2.
        (code, stdout, stderr) = CliRunner.Run(Name, "700:400:3");
        Assert.Equal(CommandLine.BadInput, code);
        Assert.Equal("", stdout);
        Assert.StartsWith($"spectral {Name}: ", stderr);
        Assert.Single(stderr.TrimEnd().Split('\n'));

        // A near miss names it.
        (code, _, stderr) = CliRunner.Run("test-band-centre", "400:700:3");
        Assert.Equal(CommandLine.BadInput, code);
        Assert.Contains(Name, stderr);
    }

    [Fact]
    public void A_name_already_taken_is_refused()
    {
        Assert.Throws<ArgumentException>(() => CommandLine.Register("render", "another render", BandCentres));
        Assert.Throws<ArgumentException>(() => CommandLine.Register("--render", "an option", BandCentres));
    }
}
