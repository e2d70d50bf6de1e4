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
/// runs (a sweep rebuilds its index), one line says what was left, and the process exits 1 — or 0 when the command had
/// finished: its output folders swapped in (<see cref="ExpectCommits"/>), none abandoned. A folder's swap and the stop
/// exclude each other (<see cref="OutputFolder"/>): the stop waits for a swap under way, a swap never starts after it.
/// </summary>
public sealed class Signals : IDisposable
{
    /// <summary>How long a command has to stop by itself after a signal before the process is ended for it.</summary>
    public static readonly TimeSpan Grace = TimeSpan.FromSeconds(0.3);

    static readonly AsyncLocal<Signals?> CurrentRun = new();

    /// <summary>0 before the process's command starts, 1 while it runs, 2 once it returned (<see cref="AnswerUntilExit"/>).</summary>
    static int _phase;
    static PosixSignalRegistration? _lateInterrupt, _lateTerminate;

    /// <summary>
    /// The process's answer outside its command's run (called once, by Program): before the command starts, the runtime's
    /// default (the process ends at once, nothing written, exit 130 or 143); once it has returned, the signal is ignored —
    /// the command finished, its output is whole, and the process exits with the command's code a moment later.
    /// </summary>
    public static void AnswerUntilExit()
    {
        try
        {
            _lateInterrupt = PosixSignalRegistration.Create(PosixSignal.SIGINT, Late);
            _lateTerminate = PosixSignalRegistration.Create(PosixSignal.SIGTERM, Late);
        }
        catch (PlatformNotSupportedException) { }
    }

    static void Late(PosixSignalContext c)
    {
        if (Volatile.Read(ref _phase) == 2) c.Cancel = true;
    }

    readonly CancellationTokenSource _cancel = new();
    readonly string _command;
    readonly TextWriter _stderr;
    readonly PosixSignalRegistration? _interrupt, _terminate;
    long _signalledAt;
    string _signal = "";
    int _ended, _commits, _expected = 1;
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
        Volatile.Write(ref _phase, 1);
        OutputFolder.Committed ??= () => Interlocked.Increment(ref Current._commits);
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

    /// <summary>How many output folders the command swaps in when it finishes (default 1; more for a relight sweep, none for a
    /// command that writes nothing, or int.MaxValue when no count of folders says it is done).</summary>
    public static void ExpectCommits(int folders) => Current._expected = folders;

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
        var (folders, abandoned) = OutputFolder.AbandonAll();   // waits for a swap under way; none starts after it
        bool finished = !abandoned && Volatile.Read(ref _commits) >= _expected;
        if (!finished)
        {
            try { _lastStep?.Invoke(); }
            catch (Exception e) when (e is IOException or UnauthorizedAccessException or InputException) { }
        }
        string left = finished ? "its output was written whole before the signal stopped it"
            : _left?.Invoke()
            ?? (folders.Count == 0 ? "nothing was written under a final name" : "nothing was written: " + string.Join("; ", folders));
        try
        {
            _stderr.WriteLine(MessageText.Line(finished
                ? $"spectral {_command}: {_signal} came after the command had finished ({StoppedAfterSelf()}); {left}"
                : $"spectral {_command}: interrupted by {_signal} ({StoppedAfterSelf()}); {left}"));
            _stderr.Flush();
        }
        catch (Exception e) when (e is IOException or ObjectDisposedException) { }
        OutputFolder.RemoveAbandonedStaging();   // a writer thread may have made a staging sub-folder anew meanwhile
        Environment.Exit(finished ? CommandLine.Success : CommandLine.Failure);
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
        Volatile.Write(ref _phase, 2);
        _interrupt?.Dispose();
        _terminate?.Dispose();
        if (ReferenceEquals(CurrentRun.Value, this)) CurrentRun.Value = null;
        _cancel.Dispose();
    }
}
