using System.Globalization;
using SpectralRenderer.Rendering;

namespace SpectralRenderer.Cli;

/// <summary>A progress bar on stderr when it is a terminal: tiles, percent, rays/s, ETA.</summary>
public sealed class ProgressBar
{
    readonly TextWriter _err;
    DateTime _last = DateTime.MinValue;

    ProgressBar(TextWriter err) { _err = err; }

    /// <summary>A bar when stderr is a terminal, else null (the summary line is enough).</summary>
    public static ProgressBar? For(TextWriter err) =>
        ReferenceEquals(err, Console.Error) && !Console.IsErrorRedirected ? new ProgressBar(err) : null;

    public void Report(RenderProgress p)
    {
        var now = DateTime.UtcNow;
        if (p.TilesDone != p.Tiles && (now - _last).TotalMilliseconds < 100) return;
        _last = now;
        double f = (double)p.TilesDone / p.Tiles;
        int filled = (int)(f * 30);
        double secs = p.Elapsed.TotalSeconds;
        double eta = f > 0 ? secs / f - secs : 0;
        _err.Write(string.Create(CultureInfo.InvariantCulture,
            $"\r[{new string('#', filled)}{new string('.', 30 - filled)}] {f * 100,5:0.0}%  {p.TilesDone}/{p.Tiles} tiles  "
                + $"{p.Rays / Math.Max(secs, 1e-9) / 1e6:0.0} Mrays/s  ETA {eta:0.0} s "));
    }

    public void Finish() => _err.Write("\r" + new string(' ', 90) + "\r");
}
