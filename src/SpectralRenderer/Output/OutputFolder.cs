using System.Diagnostics;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Output;

/// <summary>
/// A render folder that is always one whole render, the old one or the new one. The new render is written into a
/// sibling staging folder (".NAME.render-PID-ID.tmp"); when it is complete, the files the previous render.json lists
/// are moved aside into ".NAME.old-PID-ID.tmp", the new files moved in (render.json last), and the old ones removed.
/// Nothing else in the folder is touched: no file is removed by a pattern, none through a symbolic link, and a file
/// of the new render's name that the previous render did not write stops the swap (bad input, exit 2) with the old
/// render in place. Staging and aside folders of killed runs (their process id no longer alive) are removed by the
/// next run on the same folder.
/// </summary>
public sealed class OutputFolder
{
    const string StagingTag = ".render-", AsideTag = ".old-", TmpSuffix = ".tmp";

    public string Final { get; }
    /// <summary>Where the new render is written until <see cref="Commit"/>.</summary>
    public string Staging { get; }
    readonly string _parent, _name;

    OutputFolder(string final, string parent, string name)
    {
        Final = final;
        _parent = parent;
        _name = name;
        Staging = Path.Combine(parent, $".{name}{StagingTag}{Environment.ProcessId}-{Guid.NewGuid():N}{TmpSuffix}");
    }

    /// <summary>Checks the folder can take a render and creates the staging folder beside it.</summary>
    public static OutputFolder Begin(string outDir)
    {
        if (string.IsNullOrWhiteSpace(outDir)) throw new InputException("-o", "the output folder name is empty", "give a folder name, e.g. -o out/scene");
        string full;
        try { full = Path.GetFullPath(outDir).TrimEnd(Path.DirectorySeparatorChar); }
        catch (Exception e) when (e is ArgumentException or PathTooLongException or NotSupportedException)
        { throw new InputException(outDir, "is not a usable folder name", "choose another -o"); }
        if (File.Exists(full) && !Directory.Exists(full)) throw new InputException(outDir, "exists and is a file, not a folder", "choose another -o");
        var parent = Path.GetDirectoryName(full) ?? throw new InputException(outDir, "is the root folder", "choose a folder below it");
        var folder = new OutputFolder(full, parent, Path.GetFileName(full));
        try
        {
            Directory.CreateDirectory(parent);
            folder.RemoveStale();
            folder.CheckNames(["bands"]);
            Directory.CreateDirectory(folder.Staging);
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException)
        {
            string reason = e is PathTooLongException ? "the path is too long" : e.Message.Replace(full, "it").Replace(parent, "its folder");
            throw new InputException(outDir, $"cannot be written: {reason}", "choose a folder you can write to");
        }
        return folder;
    }

    /// <summary>Removes the staging folder (the new render's partial files); the final folder is as it was.</summary>
    public void Abandon()
    {
        try { if (Directory.Exists(Staging)) Directory.Delete(Staging, recursive: true); }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException) { /* best effort: the next run removes it */ }
    }

    /// <summary>Whether the final folder holds a render (a render.json) now.</summary>
    public bool HoldsRender => File.Exists(Path.Combine(Final, RenderManifest.FileName));

    /// <summary>
    /// Swaps the staged render in: <paramref name="files"/> (relative paths, render.json among them) replace the files
    /// the previous render.json lists. A name taken by a file the previous render did not write stops the swap first.
    /// </summary>
    public void Commit(IReadOnlyList<string> files)
    {
        var previous = PreviousFiles();
        CheckNames(files.Select(f => f.Split('/')[0]).Distinct(StringComparer.Ordinal), previous);
        foreach (var f in files)
        {
            var dest = Path.Combine(Final, f);
            if ((File.Exists(dest) || Directory.Exists(dest)) && !previous.Contains(f))
                throw new InputException(dest, "exists and was not written by the previous render (render.json does not list it)",
                    "move it away or choose another -o: spectral never replaces a file it did not write");
        }
        var aside = Path.Combine(_parent, $".{_name}{AsideTag}{Environment.ProcessId}-{Guid.NewGuid():N}{TmpSuffix}");
        var movedAside = new List<string>();
        var movedIn = new List<string>();
        Directory.CreateDirectory(Final);
        try
        {
            // The old render out: its render.json first, so the folder is never described by a manifest that did not write it.
            foreach (var f in previous.OrderBy(f => f == RenderManifest.FileName ? 0 : 1).ThenBy(f => f, StringComparer.Ordinal))
            {
                var src = Path.Combine(Final, f);
                if (!File.Exists(src) && !IsLink(src)) continue;
                var dst = Path.Combine(aside, f);
                Directory.CreateDirectory(Path.GetDirectoryName(dst)!);
                File.Move(src, dst);
                movedAside.Add(f);
            }
            // The new render in: render.json last.
            foreach (var f in files.OrderBy(f => f == RenderManifest.FileName ? 1 : 0))
            {
                var dst = Path.Combine(Final, f);
                Directory.CreateDirectory(Path.GetDirectoryName(dst)!);
                File.Move(Path.Combine(Staging, f), dst);
                movedIn.Add(f);
            }
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException)
        {
            // Leave no new file behind and put the old render back as it was (best effort).
            foreach (var f in movedIn) { try { File.Delete(Path.Combine(Final, f)); } catch (IOException) { } }
            foreach (var f in movedAside) { try { File.Move(Path.Combine(aside, f), Path.Combine(Final, f)); } catch (IOException) { } }
            throw;
        }
        finally
        {
            TryDelete(aside);
            TryDelete(Staging);
        }
        // Sub-folders of the old render that are empty now and not the new render's (bands/ of a render without band images).
        foreach (var dir in previous.Select(f => Path.GetDirectoryName(f)).Where(d => !string.IsNullOrEmpty(d)).Distinct())
        {
            var p = Path.Combine(Final, dir!);
            if (Directory.Exists(p) && !IsLink(p) && !Directory.EnumerateFileSystemEntries(p).Any()) Directory.Delete(p);
        }
    }

    static void TryDelete(string dir)
    {
        try { if (Directory.Exists(dir)) Directory.Delete(dir, recursive: true); }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException) { }
    }

    static bool IsLink(string path) => new FileInfo(path).LinkTarget is not null;

    /// <summary>The top-level names the render writes folders under must be real folders of the render folder, not links or files.</summary>
    void CheckNames(IEnumerable<string> names, HashSet<string>? previous = null)
    {
        foreach (var name in names)
        {
            var p = Path.Combine(Final, name);
            if (IsLink(p))
                throw new InputException(p, $"is a symbolic link to {MessageText.Quote(new FileInfo(p).LinkTarget, 80)}, not a folder of the render",
                    "remove the link or choose another -o: spectral never writes or removes through a link");
            if (name == "bands" && File.Exists(p) && previous?.Contains(name) != true)
                throw new InputException(p, "is a file where the render writes its bands/ folder", "move it away or choose another -o");
        }
    }

    /// <summary>
    /// The files the previous render.json lists, as relative paths inside the folder — only those that stay inside it:
    /// no absolute path, no "..", no component that is a symbolic link. A missing or unreadable render.json lists nothing.
    /// </summary>
    public HashSet<string> PreviousFiles()
    {
        var set = new HashSet<string>(StringComparer.Ordinal);
        var manifest = Path.Combine(Final, RenderManifest.FileName);
        if (!File.Exists(manifest) || IsLink(manifest)) return set;
        try
        {
            var length = new FileInfo(manifest).Length;
            if (length > InputFile.MaxTextBytes) return set;
            if (JsonNode.Parse(File.ReadAllText(manifest)) is not JsonObject json || json["files"] is not JsonArray list) return set;
            set.Add(RenderManifest.FileName);
            foreach (var n in list)
            {
                if (n is not JsonValue v || !v.TryGetValue<string>(out var f) || !InsideFolder(f)) continue;
                set.Add(f);
            }
        }
        catch (Exception e) when (e is JsonException or IOException or UnauthorizedAccessException or InvalidOperationException) { set.Clear(); }
        return set;
    }

    bool InsideFolder(string relative)
    {
        if (relative.Length == 0 || Path.IsPathRooted(relative) || relative.Contains('\\') || relative.Contains('\0')) return false;
        var parts = relative.Split('/');
        if (parts.Any(p => p is "" or "." or "..")) return false;
        var p = Final;
        foreach (var part in parts[..^1])
        {
            p = Path.Combine(p, part);
            if (IsLink(p) || !Directory.Exists(p)) return false;
        }
        return true;
    }

    /// <summary>Removes staging and aside folders of this folder left by runs that were killed (their process is gone).</summary>
    void RemoveStale()
    {
        if (!Directory.Exists(_parent)) return;
        foreach (var dir in Directory.EnumerateDirectories(_parent, $".{_name}.*{TmpSuffix}"))
        {
            var n = Path.GetFileName(dir);
            string rest = n[(_name.Length + 1)..];
            string? tag = rest.StartsWith(StagingTag, StringComparison.Ordinal) ? StagingTag : rest.StartsWith(AsideTag, StringComparison.Ordinal) ? AsideTag : null;
            if (tag is null || IsLink(dir)) continue;
            var idPart = rest[tag.Length..^TmpSuffix.Length];
            int dash = idPart.IndexOf('-');
            if (dash <= 0 || !int.TryParse(idPart[..dash], out int pid) || idPart.Length - dash - 1 != 32) continue;
            if (pid == Environment.ProcessId || ProcessAlive(pid)) continue;
            TryDelete(dir);
        }
    }

    /// <summary>Whether process <paramref name="pid"/> exists (Linux: /proc/PID; elsewhere by the process table).</summary>
    public static bool ProcessAlive(int pid)
    {
        if (OperatingSystem.IsLinux()) return Directory.Exists($"/proc/{pid}");
        try { using var p = Process.GetProcessById(pid); return !p.HasExited; }
        catch (ArgumentException) { return false; }
        catch (InvalidOperationException) { return false; }
    }
}
