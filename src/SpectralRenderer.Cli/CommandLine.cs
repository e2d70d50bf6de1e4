using System.Reflection;
using SpectralRenderer.Cli.Commands;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Cli;

/// <summary>The `spectral` command: dispatch, help, and the exit codes 0 success, 1 failure, 2 bad usage or input.</summary>
public static class CommandLine
{
    public const int Success = 0, Failure = 1, BadInput = 2;

    /// <summary>
    /// The commands, one line each: name, its line in `spectral --help`, and its handler (the arguments after the name,
    /// stdout, stderr → exit code; an exception becomes one line on stderr and its exit code, <see cref="Describe"/>).
    /// A new command is one file in Commands/ and one line here, or a <see cref="Register"/> call.
    /// </summary>
    static readonly List<Command> Commands =
    [
        new("render", "render a scene file: band images, spectral cubes, sRGB preview", RenderCommand.Run),
        new("colorcheck", "a rendered ColorChecker's patches against their 1 nm reference (ΔE00)", ColorCheckCommand.Run),
        new("experiments", "every scene of the paper rendered and analysed into report.html (Figs. 2–7)", ExperimentsCommand.Run),
        new("bench", "load, BVH build and render times, Mrays/s, peak memory", BenchCommand.Run),
        new("colors", "the 24 ColorChecker patches' XYZ, Lab, RGB and ΔE00 under a light", ColorsCommand.Run),
        new("probe", "the spectra of chosen pixels of a render, as CSV and an SVG plot (Fig. 6b)", ProbeCommand.Run),
        new("relight", "a render under other lights, exactly, from its per-light outputs (no rays traced)", RelightCommand.Run),
        new("view", "the spectral viewer (viewer.html) of a render; --serve serves it on loopback", ViewCommand.Run),
        new("merge", "the shards of a render (render --shard I/N) assembled into the whole render, byte for byte", MergeCommand.Run),
        new("sweep", "a plan's jobs (scene × lights × materials × …) rendered into a dataset with an index, locally or as a job array",
            SweepCommand.Run),
        new("reconstruct", "white-board reflectance reconstruction against the truth, by region (§3.4, Fig. 7)", ReconstructCommand.Run),
        new("camera", "a render seen by a simulated camera: raw (NPY, PNG, DNG), processed sRGB, ΔE00 and SNR per patch",
            CameraCommand.Run),
        new("recover", "spectral reflectance from a camera's signals (pinv, Wiener, linear model, Tikhonov) against the truth",
            RecoverCommand.Run),
        new("metamerism", "an sRGB texture's colour under other lights for two metamers of its uplift (ΔE00 spread)",
            MetamerismCommand.Run),
        new("illuminance", "illuminance (lx) on a grid of points of a work plane from every light: CSV and an SVG heat map",
            IlluminanceCommand.Run),
        new("import", "a Mitsuba 3 XML, pbrt-v4 or glTF 2.0 scene converted to our scene JSON, with a report of what was approximated",
            ImportCommand.Run),
        new("validate", "the tool's accuracy: CIE 171-style lighting, radiometric, colour and camera cases against closed forms",
            ValidateCommand.Run),
    ];

    /// <summary>Adds a command (a plug-in, a test) after the built-in ones; its name is lower-case letters, digits and '-'.</summary>
    public static void Register(string name, string summary, Func<string[], TextWriter, TextWriter, int> run)
    {
        ArgumentNullException.ThrowIfNull(run);
        if (string.IsNullOrEmpty(name) || name[0] == '-' || !name.All(c => char.IsAsciiLetterLower(c) || char.IsAsciiDigit(c) || c == '-'))
            throw new ArgumentException($"a command name is lower-case letters, digits and '-', not '{name}'", nameof(name));
        if (summary.Contains('\n')) throw new ArgumentException("a command's summary is one line", nameof(summary));
        lock (Commands)
        {
            if (name is "help" || Commands.Any(c => c.Name == name))
                throw new ArgumentException($"the command '{name}' exists already", nameof(name));
            Commands.Add(new(name, summary, run));
        }
    }

    /// <summary>The commands' names, in the order of `spectral --help`.</summary>
    public static string[] Names => [.. Table().Select(c => c.Name)];

    static Command[] Table()
    {
        lock (Commands) return [.. Commands];
    }

    /// <summary>A command: its name, its line in `spectral --help` and its handler. A class, not a tuple: a list of tuples of
    /// references is a generic instantiation the ReadyToRun image cannot hold, compiled at every start.</summary>
    sealed record Command(string Name, string Summary, Func<string[], TextWriter, TextWriter, int> Run);

    public static string Version => typeof(CommandLine).Assembly.GetName().Version?.ToString(3) ?? "0.0.0";

    public static int Run(string[] args, TextWriter stdout, TextWriter stderr)
    {
        // `spectral help COMMAND` is `spectral COMMAND --help`.
        if (args is ["help", var topic] && topic is not ("--help" or "-h" or "help")) args = [topic, "--help"];
        if (args.Length == 0 || args[0] is "--help" or "-h" or "help")
        {
            stdout.Write(Usage());
            return args.Length == 0 ? BadInput : Success;
        }
        if (args[0] == "--version") { stdout.WriteLine($"spectral {Version}"); return Success; }
        var commands = Table();
        Command? cmd = null;
        foreach (var c in commands) if (c.Name == args[0]) { cmd = c; break; }
        if (cmd is null)
        {
            stderr.WriteLine($"spectral: unknown command '{args[0]}' (hint: "
                + $"{InputException.DidYouMean(args[0], commands.Select(c => c.Name)) ?? "see 'spectral --help'"})");
            return BadInput;
        }
        // SIGINT and SIGTERM are answered from here to the exit (Signals): the command stops at its next check, or is
        // ended for it after a grace period with its staging removed and one line of what was left.
        using var signals = Signals.Install(cmd.Name, stderr);
        int exit;
        string? line = null;
        try
        {
            exit = cmd.Run(args[1..], stdout, stderr);
        }
        catch (Exception e)
        {
            var (code, message) = Describe(e);
            // An InputException's message is one line of at most MessageText.MaxLine already, cut where its parts allow
            // (never through its hint); other messages are made one such line here.
            line = $"spectral {cmd.Name}: " + (e is InputException ? MessageText.Escape(message) : MessageText.Line(message));
            exit = code;
        }
        if (!signals.TryEnd()) Thread.Sleep(Timeout.Infinite);   // a signal's watchdog is ending the process with its own line
        if (line is not null) stderr.WriteLine(line);
        return exit;
    }

    /// <summary>
    /// The exit code and the one line an exception ends a command with: bad input (2) says where and what with a
    /// hint; a failure of the work (1) says what failed. A defect of the program is still one line, never a trace.
    /// </summary>
    public static (int Code, string Message) Describe(Exception e)
    {
        if (e is AggregateException agg && agg.Flatten().InnerExceptions.Count > 0) e = agg.Flatten().InnerExceptions[0];
        if (e is TargetInvocationException { InnerException: { } inner }) e = inner;
        return e switch
        {
            InputException => (BadInput, e.Message),
            WorkFailedException or InterruptedException => (Failure, e.Message),
            OperationCanceledException => (Failure, "interrupted; no output was left under a final name"),
            OutOfMemoryException or InsufficientExecutionStackException =>
                (Failure, $"out of memory ({e.GetType().Name}) (hint: lower the resolution, band count or mesh size)"),
            IOException => (Failure, e.Message),
            UnauthorizedAccessException => (BadInput, $"{e.Message} (hint: choose files and folders you can read and write)"),
            _ => (Failure,
                $"internal error {e.GetType().Name}: {e.Message} (hint: this is a defect of spectral; please report it with the input)"),
        };
    }

    static string Usage()
    {
        var w = new StringWriter();
        w.WriteLine($"spectral {Version} — a spectral ray tracer (Li et al. 2010, eq. 2–4) with CIE-exact colour");
        w.WriteLine();
        w.WriteLine("usage: spectral <command> [options]     spectral <command> --help for its options");
        w.WriteLine();
        foreach (var c in Table()) w.WriteLine($"  {c.Name,-12} {c.Summary}");
        w.WriteLine();
        w.WriteLine("exit codes: 0 success, 1 failure, 2 bad usage or bad input");
        return w.ToString();
    }
}
