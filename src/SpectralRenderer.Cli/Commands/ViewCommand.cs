using System.Globalization;
using System.Net;
using System.Net.Sockets;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Relighting;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral view OUTDIR [--serve]`: the spectral viewer page, written into the render folder and optionally served on
/// loopback.</summary>
public static class ViewCommand
{
    const string Help = """
        usage: spectral view OUTDIR [--serve] [--port N] [--for SECONDS]

        Writes OUTDIR/viewer.html (self-contained: no network references) and its data OUTDIR/viewer-data.js.
        Open viewer.html in a browser (file:// works), or serve the folder with --serve. The page shows the
        sRGB image with exposure and gamut controls, the spectrum of the pixel under the mouse (click to pin)
        with the ground-truth reflectance of the object seen, each band image (Fig. 2), region means
        (shift-drag), and — for renders with the per-light outputs (--formats …,lights) — a light picker
        and intensity sliders (linear, and logarithmic over four decades) that relight the image in the page,
        with Ra and Rf of each light and a ΔE00 map between a stored lighting state and the current one. A
        render with --formats …,photometry adds its luminance (cd/m²) and illuminance (lx) maps as views (false
        colour with the legend of luminance.png and illuminance.png) and both values under the cursor; they
        follow the lights as they change (illuminance: each light's share traced again when the page is written).

          --serve          serve OUTDIR on http://127.0.0.1:PORT/ (System.Net.HttpListener) and print the URL
          --port N         the port (default: a free one)
          --for SECONDS    stop serving after SECONDS (default: until Ctrl+C)
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("view", argv, ["--port", "--for"], ["--serve"]);
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1) throw new InputException("", "give one render folder", "usage: spectral view OUTDIR [--serve]");
        var dir = a.Positionals[0];
        int? port = a.Int("--port", 1, 65535);
        double? seconds = a.Double("--for", 0, 1e7, "seconds");   // ≤ 116 days: a TimeSpan holds it
        var files = SpectralViewer.Write(dir);
        var page = Path.Combine(Path.GetFullPath(dir), "viewer.html");
        if (!a.Flag("--serve"))
        {
            stdout.WriteLine($"wrote {string.Join(" and ", files)} to {dir}; open file://{page}");
            return CommandLine.Success;
        }
        // Until --for ends or SIGINT/SIGTERM (Signals) comes: then the listener stops and the command says so.
        using var cancel = CancellationTokenSource.CreateLinkedTokenSource(Signals.Token);
        if (seconds is { } s) cancel.CancelAfter(TimeSpan.FromSeconds(s));
        Serve(Path.GetFullPath(dir), port ?? FreePort(), stdout, cancel.Token);
        if (Signals.Token.IsCancellationRequested)
            stderr.WriteLine(
                $"spectral view: stopped serving on {Signals.Signal}{Signals.StoppedAfter()}; {string.Join(" and ", files)} stay in {dir}");
        return CommandLine.Success;
    }

    static int FreePort()
    {
        var l = new TcpListener(IPAddress.Loopback, 0);
        l.Start();
        int p = ((IPEndPoint)l.LocalEndpoint).Port;
        l.Stop();
        return p;
    }

    /// <summary>Serves the files of <paramref name="root"/> (and nothing outside it) until cancelled.</summary>
    static void Serve(string root, int port, TextWriter stdout, CancellationToken cancel)
    {
        using var listener = new HttpListener();
        listener.Prefixes.Add($"http://127.0.0.1:{port.ToString(CultureInfo.InvariantCulture)}/");
        try { listener.Start(); }
        catch (HttpListenerException e)
        {
            throw new InputException("--port", $"cannot listen on 127.0.0.1:{port}: {e.Message}", "choose another --port");
        }
        stdout.WriteLine($"serving {root} at http://127.0.0.1:{port}/viewer.html");
        stdout.Flush();
        using var stop = cancel.Register(() => { try { listener.Stop(); } catch (ObjectDisposedException) { } });
        while (!cancel.IsCancellationRequested)
        {
            HttpListenerContext ctx;
            try { ctx = listener.GetContext(); }
            catch (Exception e) when (e is HttpListenerException or ObjectDisposedException or InvalidOperationException) { break; }
            try { Answer(root, ctx); }
            catch (Exception e) when (e is HttpListenerException or IOException) { /* the client went away */ }
        }
    }

    static void Answer(string root, HttpListenerContext ctx)
    {
        var res = ctx.Response;
        var rel = Uri.UnescapeDataString(ctx.Request.Url?.AbsolutePath ?? "/").TrimStart('/');
        if (rel.Length == 0) rel = "viewer.html";
        var path = Path.GetFullPath(Path.Combine(root, rel));
        bool inside = path.StartsWith(root + Path.DirectorySeparatorChar, StringComparison.Ordinal);
        if (ctx.Request.HttpMethod is not ("GET" or "HEAD") || !inside || !File.Exists(path))
        {
            res.StatusCode =
                inside || ctx.Request.HttpMethod is not ("GET" or "HEAD") ? (ctx.Request.HttpMethod is "GET" or "HEAD" ? 404 : 405) : 403;
            res.Close();
            return;
        }
        res.ContentType = Path.GetExtension(path).ToLowerInvariant() switch
        {
            ".html" => "text/html; charset=utf-8",
            ".js" => "text/javascript; charset=utf-8",
            ".json" => "application/json",
            ".png" => "image/png",
            ".svg" => "image/svg+xml",
            ".csv" => "text/csv; charset=utf-8",
            _ => "application/octet-stream",
        };
        res.Headers["Cache-Control"] = "no-store";
        using var f = File.OpenRead(path);
        res.ContentLength64 = f.Length;
        if (ctx.Request.HttpMethod == "GET") f.CopyTo(res.OutputStream);
        res.Close();
    }
}
