namespace SpectralRenderer.Diagnostics;

/// <summary>The work failed (not the input): one line saying what failed and what was left on disk. The CLI exits with code 1.</summary>
public sealed class WorkFailedException(string message) : Exception(MessageText.Line(message));

/// <summary>
/// The run was interrupted (SIGINT, SIGTERM): its message says truthfully what was done and what is left on disk.
/// The CLI exits with code 1.
/// </summary>
public sealed class InterruptedException(string message, CancellationToken token = default)
    : OperationCanceledException(MessageText.Line(message), token);
