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

    readonly Lock _gate = new();

    /// <summary>Redraws the bar (at most every 100 ms, and at the end); called from any thread (a gather's rows report in
    /// parallel).</summary>
    public void Report(RenderProgress p)
    {
        lock (_gate) Draw(p);
    }

    void Draw(RenderProgress p)
    {
        var now = DateTime.UtcNow;
        if (p.TilesDone != p.Tiles && (now - _last).TotalMilliseconds < 100) return;
        _last = now;
        double f = (double)p.TilesDone / p.Tiles;
        int filled = (int)(f * 30);
        double secs = p.Elapsed.TotalSeconds;
        double eta = f > 0 ? secs / f - secs : 0;
        // The render's tiles and its ray rate; a product's gather after it (p.Stage) in rows, its rays not counted.
        string what = p.Stage is null
            ? string.Create(CultureInfo.InvariantCulture,
                $"{p.TilesDone}/{p.Tiles} tiles  {p.Rays / Math.Max(secs, 1e-9) / 1e6:0.0} Mrays/s")
            : $"{p.TilesDone}/{p.Tiles} rows of the {p.Stage}";
        _err.Write(string.Create(CultureInfo.InvariantCulture,
            $"\r[{new string('#', filled)}{new string('.', 30 - filled)}] {f * 100,5:0.0}%  {what}  ETA {eta:0.0} s "));
    }

    public void Finish() => _err.Write("\r" + new string(' ', 90) + "\r");
}
