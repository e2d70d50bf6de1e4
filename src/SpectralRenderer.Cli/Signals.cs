using System.Diagnostics;
using System.Globalization;
using System.Runtime.InteropServices;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Output;

namespace SpectralRenderer.Cli;

/// <summary>
/// SIGINT and SIGTERM from a command's start to its exit. The first signal cancels <see cref="Token"/>, which the
/// command's loops check, so it stops at its next check and says what it left. Should it still be working
/// <see cref="Grace"/> later (a mesh being read, one long step without a check), the signal ends it here: the staging
/// of every folder not yet swapped in is removed (<see cref="OutputFolder.AbandonAll"/>), the command's own last step
/// runs (a sweep rebuilds its index), one line says what was left, and the process exits 1.
/// </summary>
public sealed class Signals : IDisposable
{
    /// <summary>How long a command has to stop by itself after a signal before the process is ended for it.</summary>
    public static readonly TimeSpan Grace = TimeSpan.FromSeconds(0.3);

    static readonly AsyncLocal<Signals?> CurrentRun = new();

    readonly CancellationTokenSource _cancel = new();
    readonly string _command;
    readonly TextWriter _stderr;
    readonly PosixSignalRegistration? _interrupt, _terminate;
    long _signalledAt;
    string _signal = "";
    int _ended;
    volatile Action? _lastStep;
    volatile Func<string>? _left;

    Signals(string command, TextWriter stderr, bool register)
    {
        _command = command;
        _stderr = stderr;
        if (!register) return;
        try
        {
            _interrupt = PosixSignalRegistration.Create(PosixSignal.SIGINT, On);
            _terminate = PosixSignalRegistration.Create(PosixSignal.SIGTERM, On);
        }
        catch (PlatformNotSupportedException) { }
    }

    /// <summary>Starts answering signals for the command about to run (on this thread and the tasks it starts).</summary>
    public static Signals Install(string command, TextWriter stderr)
    {
        var s = new Signals(command, stderr, register: true);
        CurrentRun.Value = s;
        return s;
    }

    static Signals Current => CurrentRun.Value ??= new Signals("", TextWriter.Null, register: false);

    /// <summary>Cancelled by the first SIGINT or SIGTERM.</summary>
    public static CancellationToken Token => Current._cancel.Token;

    /// <summary>The signal's name (SIGINT, SIGTERM), or "" before one came.</summary>
    public static string Signal => Current._signal;

    /// <summary>", 0.120 s after the signal" once a signal came, else "".</summary>
    public static string StoppedAfter()
    {
        long at = Interlocked.Read(ref Current._signalledAt);
        return at == 0
            ? ""
            : string.Create(CultureInfo.InvariantCulture, $", {Stopwatch.GetElapsedTime(at).TotalSeconds:0.000} s after the signal");
    }

    /// <summary>What runs before the process is ended for a signal (a sweep rebuilds its index).</summary>
    public static void OnForcedStop(Action lastStep) => Current._lastStep = lastStep;

    /// <summary>What the one line says was left, when the process is ended for a signal (default: each open output folder's
    /// state).</summary>
    public static void DescribeLeft(Func<string> left) => Current._left = left;

    /// <summary>Tests: a signal as the handler receives it.</summary>
    internal void Raise(PosixSignal signal) => Receive(signal);

    void On(PosixSignalContext c)
    {
        c.Cancel = true;   // the command stops itself (or the watchdog ends it); the runtime does not kill it
        Receive(c.Signal);
    }

    void Receive(PosixSignal signal)
    {
        if (Interlocked.CompareExchange(ref _signalledAt, Stopwatch.GetTimestamp(), 0) != 0) return;
        _signal = signal == PosixSignal.SIGINT ? "SIGINT" : signal == PosixSignal.SIGTERM ? "SIGTERM" : signal.ToString();
        _cancel.Cancel();
        new Thread(Watchdog) { IsBackground = true, Name = "signal watchdog" }.Start();
    }

    void Watchdog()
    {
        Thread.Sleep(Grace);
        if (!TryEnd()) return;   // the command ended by itself
        try { _lastStep?.Invoke(); }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException or InputException) { }
        var folders = OutputFolder.AbandonAll();
        string left = _left?.Invoke()
            ?? (folders.Count == 0 ? "nothing was written under a final name" : "nothing was written: " + string.Join("; ", folders));
        try
        {
            _stderr.WriteLine(MessageText.Line($"spectral {_command}: interrupted by {_signal} ({StoppedAfterSelf()}); {left}"));
            _stderr.Flush();
        }
        catch (Exception e) when (e is IOException or ObjectDisposedException) { }
        Environment.Exit(CommandLine.Failure);
    }

    string StoppedAfterSelf() => string.Create(CultureInfo.InvariantCulture,
        $"stopped {Stopwatch.GetElapsedTime(Interlocked.Read(ref _signalledAt)).TotalSeconds:0.000} s after the signal");

    /// <summary>
    /// Claims the command's end: true for the first caller (the command returning, or the watchdog); the other must not
    /// write its line. A command that returns after the watchdog claimed it waits for the process to end.
    /// </summary>
    internal bool TryEnd() => Interlocked.Exchange(ref _ended, 1) == 0;

    public void Dispose()
    {
        _interrupt?.Dispose();
        _terminate?.Dispose();
        if (ReferenceEquals(CurrentRun.Value, this)) CurrentRun.Value = null;
        _cancel.Dispose();
    }
}
