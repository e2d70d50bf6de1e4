using System.Diagnostics;
using System.Text.Json;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Output;

/// <summary>
/// The one folder transaction of every command that writes: a folder that is always one whole result, the old one or
/// the new one. The new files are written into a sibling staging folder (".NAME.render-PID-ID.tmp"); when they are
/// complete, a journal (".NAME.journal": the staging and aside folders, the old and new file names) is written, the
/// files the previous manifest lists (render.json, camera.json; for outputs added into a folder, the names this command
/// writes) are moved aside into ".NAME.old-PID-ID.tmp", the new files moved in (the manifest last), and the aside,
/// staging and journal removed. A run killed at any instant of the swap leaves the journal, and the next run on the
/// folder finishes that swap first (every step can be redone), so the folder holds one whole result.
/// An advisory lock (".NAME.lock" beside the folder, flock) keeps a second writer out: it stops with bad input naming
/// the folder. Nothing else in the folder is touched: no file is removed by a pattern, none through a symbolic link,
/// and a file of a new name that the previous run did not write stops the swap with the old files in place. Staging and
/// aside folders of killed runs (their process gone, no journal naming them) are removed by the next run on the folder.
/// A stop (a signal: <see cref="Commit"/>'s token, or <see cref="AbandonAll"/>) and the swap exclude each other: the
/// token is checked once inside the swap's lock, before the journal — the one point where the new result is decided —
/// and a stop that comes after it waits for the swap to end. So a stopped command leaves the old folder whole (and
/// exits non-zero), or the new one whole (its result was written), never a mix, a staging folder or a lock.
/// </summary>
public sealed class OutputFolder : IDisposable
{
    const string StagingTag = ".render-", AsideTag = ".old-", TmpSuffix = ".tmp", LockSuffix = ".lock", JournalSuffix = ".journal";

    /// <summary>The folder (its real path: symbolic links resolved).</summary>
    public string Final { get; }
    /// <summary>Where the new files are written until <see cref="Commit"/>.</summary>
    public string Staging { get; }
    /// <summary>The manifest that lists the folder's files (render.json, camera.json); null for outputs added into a folder.</summary>
    public string? Manifest { get; }
    /// <summary>What the folder holds, for messages: "render", "camera run", "probe".</summary>
    public string What { get; }
    readonly string _parent, _name;
    readonly HashSet<string>? _owned;
    readonly object _sync = new();
    FileStream? _lock;
    bool _swapping, _done, _abandoned;

    static readonly List<OutputFolder> Live = [];
    /// <summary>Set by <see cref="AbandonAll"/>: the process is stopping, no folder begins or swaps in any more.</summary>
    static bool _stopping;
    static readonly List<string> Abandoned = [];

    /// <summary>Called on the committing thread when a swap has ended (the new result is whole in its folder): the CLI
    /// counts a command's commits to tell a finished command from an interrupted one.</summary>
    public static Action? Committed;

    /// <summary>
    /// Fault injection for tests: called after each step of a swap (1 = journal written, then each move, then the
    /// clean-up) with the folder and the step. Throwing from it leaves the folder as a kill at that step would.
    /// </summary>
    internal static Action<string, int>? SwapStep;

    /// <summary>SPECTRAL_TEST_KILL_AT_SWAP_STEP=N: the process kills itself (SIGKILL) after step N of a swap (tests).</summary>
    static readonly int KillAtStep = int.TryParse(Environment.GetEnvironmentVariable("SPECTRAL_TEST_KILL_AT_SWAP_STEP"), out int k) ? k : 0;

    /// <summary>SPECTRAL_TEST_STAGE_DELAY_MS=N: a pause once the staging folder exists (tests send a signal into it).</summary>
    static readonly int StageDelay = int.TryParse(Environment.GetEnvironmentVariable("SPECTRAL_TEST_STAGE_DELAY_MS"), out int ms) ? ms : 0;

    OutputFolder(string final, string parent, string name, string? manifest, string what, HashSet<string>? owned)
    {
        Final = final;
        _parent = parent;
        _name = name;
        Manifest = manifest;
        What = what;
        _owned = owned;
        Staging = Path.Combine(parent, $".{name}{StagingTag}{Environment.ProcessId}-{Guid.NewGuid():N}{TmpSuffix}");
    }

    string LockPath => Path.Combine(_parent, $".{_name}{LockSuffix}");
    string JournalPath => Path.Combine(_parent, $".{_name}{JournalSuffix}");

    /// <summary>Checks the folder can take a render, locks it, finishes a killed run's swap and creates the staging folder.</summary>
    public static OutputFolder Begin(string outDir) => Begin(outDir, RenderManifest.FileName, "render");

    /// <summary>
    /// As <see cref="Begin(string)"/> for a folder whose files <paramref name="manifest"/> lists (its "files" array);
    /// <paramref name="what"/> names what it holds in messages.
    /// </summary>
    public static OutputFolder Begin(string outDir, string manifest, string what) => Open(outDir, manifest, what, null, "-o");

    /// <summary>
    /// Outputs added into a folder that holds other things (recover's, probe's, reconstruct's, the viewer's files): the
    /// <paramref name="names"/> are this command's, replaced whole together; nothing else in the folder is touched.
    /// </summary>
    public static OutputFolder BeginFiles(string dir, IEnumerable<string> names, string what, string option = "-o")
    {
        var owned = new HashSet<string>(StringComparer.Ordinal);
        foreach (var n in names)
        {
            if (!JsonFields.IsRelativeName(n, out var why))
                throw new InputException(option, $"the file name {MessageText.Quote(n, 80)} {why}", "give a plain file name");
            owned.Add(n);
        }
        return Open(dir, null, what, owned, option);
    }

    static OutputFolder Open(string outDir, string? manifest, string what, HashSet<string>? owned, string option)
    {
        if (string.IsNullOrWhiteSpace(outDir))
            throw new InputException(option, "the output folder name is empty", "give a folder name, e.g. -o out/scene");
        string full;
        try { full = RealPath(Path.GetFullPath(outDir).TrimEnd(Path.DirectorySeparatorChar)); }
        catch (Exception e) when (e is ArgumentException or PathTooLongException or NotSupportedException or IOException)
        { throw new InputException(outDir, "is not a usable folder name", $"choose another {option}"); }
        if (File.Exists(full) && !Directory.Exists(full))
            throw new InputException(outDir, "exists and is a file, not a folder", $"choose another {option}");
        var parent = Path.GetDirectoryName(full) ?? throw new InputException(outDir, "is the root folder", "choose a folder below it");
        var folder = new OutputFolder(full, parent, Path.GetFileName(full), manifest, what, owned);
        lock (Live)
        {
            if (_stopping) throw new InterruptedException($"interrupted before {full} was opened: nothing was written");
            Live.Add(folder);
        }
        // Held while the lock and the staging are made: a stop (AbandonAll) waits for them and then removes them.
        Monitor.Enter(folder._sync);
        try
        {
            if (folder._abandoned) throw new InterruptedException($"interrupted before {full} was opened: nothing was written");
            Directory.CreateDirectory(parent);
            folder.TakeLock(outDir);
            folder.Recover();
            folder.RemoveStale();
            if (manifest == RenderManifest.FileName) folder.CheckNames(["bands"]);
            Directory.CreateDirectory(folder.Staging);
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException)
        {
            folder.Release();
            string reason = e is PathTooLongException
                ? "the path is too long"
                : e.Message.Replace(full, "it").Replace(parent, "its folder");
            throw new InputException(outDir, $"cannot be written: {reason}", "choose a folder you can write to");
        }
        catch
        {
            folder.Release();
            throw;
        }
        finally { Monitor.Exit(folder._sync); }
        if (StageDelay > 0) Thread.Sleep(StageDelay);
        return folder;
    }

    /// <summary>
    /// The folder's advisory lock: ".NAME.lock" beside it, held exclusively (flock) until the swap is done or abandoned.
    /// A second writer finds it held and stops (bad input, exit 2) naming the folder. The lock file is removed on release;
    /// a lock taken on a file that its holder removed meanwhile is taken again on the new file.
    /// </summary>
    void TakeLock(string given)
    {
        for (int attempt = 0; attempt < 8; attempt++)
        {
            FileStream fs;
            try { fs = new FileStream(LockPath, FileMode.OpenOrCreate, FileAccess.ReadWrite, FileShare.None); }
            catch (IOException e) when (File.Exists(LockPath) && e is not PathTooLongException)
            {
                throw new InputException(given,
                    $"is being written by another spectral process (its lock {Path.GetFileName(LockPath)} is held)",
                    "wait for that run to finish, or write to another folder");
            }
            if (!LockFileRemoved(fs)) { _lock = fs; return; }
            fs.Dispose();   // its holder removed the file between our open and our lock: lock the new one
        }
        throw new InputException(given, "cannot be locked: its lock file keeps changing",
            "wait for the other spectral processes to finish");
    }

    /// <summary>Whether the locked file is no longer at its path (Linux: /proc/self/fd says "(deleted)").</summary>
    static bool LockFileRemoved(FileStream fs)
    {
        if (!OperatingSystem.IsLinux()) return false;
        try
        {
            var target = new FileInfo($"/proc/self/fd/{fs.SafeFileHandle.DangerousGetHandle()}").LinkTarget;
            return target is null || target.EndsWith(" (deleted)", StringComparison.Ordinal);
        }
        catch (IOException) { return false; }
    }

    void Release()
    {
        lock (Live) Live.Remove(this);
        if (_lock is null) return;
        // Removed while still held, so a waiting writer that opened it sees a removed file and locks the new one.
        if (OperatingSystem.IsLinux()) { try { File.Delete(LockPath); } catch (IOException) { } catch (UnauthorizedAccessException) { } }
        _lock.Dispose();
        _lock = null;
    }

    /// <summary>
    /// Removes the staging folder (the new files) and releases the lock; the folder is as it was. Once the swap has begun
    /// (the journal is written) nothing is removed: the journal finishes it on the next run.
    /// </summary>
    public void Abandon()
    {
        lock (_sync)
        {
            if (!_swapping && !_done) TryDelete(Staging);
            Release();
        }
    }

    /// <summary>Abandons the folder unless it was swapped in (<see cref="Abandon"/>): `using` a folder removes its staging on every
    /// exit.</summary>
    public void Dispose() => Abandon();

    /// <summary>
    /// Every folder of this process not yet swapped in, abandoned (a signal's last step); their descriptions for the message.
    /// A swap under way is waited for (it only renames files): its folder then holds the new result, whole. From here on
    /// no folder of this process begins or swaps in. <c>Abandoned</c>: whether a folder lost its new result.
    /// </summary>
    public static (IReadOnlyList<string> Left, bool Abandoned) AbandonAll()
    {
        OutputFolder[] live;
        lock (Live)
        {
            _stopping = true;
            live = [.. Live];
        }
        var left = new List<string>();
        bool abandoned = false;
        foreach (var f in live)
        {
            lock (f._sync)
            {
                if (f._done)
                {
                    left.Add($"{f.Final} holds the new {f.What}, whole");
                    continue;
                }
                bool had = f.HoldsResult;
                f._abandoned = abandoned = true;
                if (!f._swapping)
                {
                    lock (Abandoned) Abandoned.Add(f.Staging);
                    TryDelete(f.Staging);
                }
                f.Release();
                left.Add(f._owned is not null ? $"{f.Final} is as it was (no {f.What} file replaced)"
                    : $"{f.Final} {(had ? $"still holds the previous {f.What}, unchanged" : $"holds no {f.What}")}");
            }
        }
        return (left, abandoned);
    }

    /// <summary>
    /// Removes the staging folders of <see cref="AbandonAll"/> again: a writer thread still running may have made one
    /// anew (a sub-folder of its files) before the process ends.
    /// </summary>
    public static void RemoveAbandonedStaging()
    {
        string[] stagings;
        lock (Abandoned) stagings = [.. Abandoned];
        foreach (var s in stagings) TryDelete(s);
    }

    /// <summary>Whether the final folder holds a render (a render.json) now.</summary>
    public bool HoldsRender => File.Exists(Path.Combine(Final, RenderManifest.FileName));

    /// <summary>Whether the final folder holds this kind of result now (its manifest, or any of the owned names).</summary>
    public bool HoldsResult =>
        Manifest is { } m ? File.Exists(Path.Combine(Final, m)) : _owned!.Any(n => File.Exists(Path.Combine(Final, n)));

    /// <summary>
    /// Swaps the staged files in: <paramref name="files"/> (relative paths; the manifest among them) replace the files
    /// the previous manifest lists. A name taken by a file the previous run did not write stops the swap first.
    /// </summary>
    /// <param name="cancel">Checked once, inside the swap's lock before its journal (the commit point): cancelled there, the
    /// staging is removed, the folder keeps what it held and an <see cref="InterruptedException"/> says so; cancelled
    /// later, the swap ends first.</param>
    public void Commit(IReadOnlyList<string> files, CancellationToken cancel = default)
    {
        HashSet<string> previous;
        try
        {
            previous = PreviousFiles();
            CheckNames(files.Select(f => f.Split('/')[0]).Distinct(StringComparer.Ordinal), previous);
            foreach (var f in files)
            {
                if (!JsonFields.IsRelativeName(f, out var why)) throw new InvalidOperationException($"file name '{f}' {why}");
                var dest = Path.Combine(Final, f);
                if ((File.Exists(dest) || Directory.Exists(dest)) && !previous.Contains(f))
                    throw new InputException(dest,
                        $"exists and was not written by the previous {What} ({Manifest ?? "it"} does not list it)",
                        "move it away or choose another -o: spectral never replaces a file it did not write");
            }
            Directory.CreateDirectory(Final);
        }
        catch
        {
            Abandon();
            throw;
        }
        var journal = new Journal(Path.GetFileName(Staging), $".{_name}{AsideTag}{Environment.ProcessId}-{Guid.NewGuid():N}{TmpSuffix}",
            Manifest, [.. previous.Order(StringComparer.Ordinal)], [.. files]);
        lock (_sync)
        {
            if (_abandoned || cancel.IsCancellationRequested)
            {
                bool had = HoldsResult;
                if (!_abandoned) TryDelete(Staging);
                Release();
                throw new InterruptedException($"interrupted before the new {What} was swapped in: its files were removed; "
                    + (_owned is not null ? $"{Final} is as it was (no {What} file replaced)"
                        : $"{Final} {(had ? $"still holds the previous {What}, unchanged" : $"holds no {What}")}"), cancel);
            }
            int step = 0;
            try
            {
                AtomicFile.WriteAllText(JournalPath, journal.ToJson());
                _swapping = true;
                Step(++step);
                Finish(journal, ref step);
            }
            catch (Exception e) when (e is IOException or UnauthorizedAccessException)
            {
                RollBack(journal);
                _swapping = false;
                TryDelete(Staging);
                Release();
                throw;
            }
            catch
            {
                Release();   // as a kill would: the journal and the files stay for the next run to finish the swap
                throw;
            }
            _done = true;
            _swapping = false;
            Release();
            Committed?.Invoke();
        }
    }

    void Step(int step)
    {
        if (step < 0) return;
        SwapStep?.Invoke(Final, step);
        if (step == KillAtStep) Process.GetCurrentProcess().Kill();
    }

    /// <summary>
    /// The swap of <paramref name="j"/> from wherever it stopped: each step is done only if it is not done yet, so a run
    /// killed at any instant is finished by doing it again. Old files out (the manifest first), new in (the manifest last),
    /// then the aside and staging folders and the journal removed.
    /// </summary>
    void Finish(Journal j, ref int step)
    {
        var staging = Path.Combine(_parent, j.Staging);
        var aside = Path.Combine(_parent, j.Aside);
        var newFiles = new HashSet<string>(j.Files, StringComparer.Ordinal);
        foreach (var f in j.Previous.OrderBy(f => f == j.Manifest ? 0 : 1).ThenBy(f => f, StringComparer.Ordinal))
        {
            var src = Path.Combine(Final, f);
            if (!File.Exists(src) && !IsLink(src)) continue;
            if (newFiles.Contains(f) && !File.Exists(Path.Combine(staging, f))) continue;   // the new file is in already
            var dst = Path.Combine(aside, f);
            Directory.CreateDirectory(Path.GetDirectoryName(dst)!);
            File.Move(src, dst, overwrite: true);
            Step(++step);
        }
        foreach (var f in j.Files.OrderBy(f => f == j.Manifest ? 1 : 0))
        {
            var src = Path.Combine(staging, f);
            if (!File.Exists(src)) continue;   // moved in already
            var dst = Path.Combine(Final, f);
            Directory.CreateDirectory(Path.GetDirectoryName(dst)!);
            File.Move(src, dst);
            Step(++step);
        }
        TryDelete(aside);
        Step(++step);
        TryDelete(staging);
        Step(++step);
        // Sub-folders of the old files that are empty now and not the new ones' (bands/ of a render without band images).
        foreach (var dir in j.Previous.Select(f => Path.GetDirectoryName(f)).Where(d => !string.IsNullOrEmpty(d)).Distinct())
        {
            var p = Path.Combine(Final, dir!);
            if (Directory.Exists(p) && !IsLink(p) && !Directory.EnumerateFileSystemEntries(p).Any()) Directory.Delete(p);
        }
        File.Delete(JournalPath);
        Step(++step);
    }

    /// <summary>An I/O failure during the swap: the new files out, the old ones back (best effort), the journal removed.</summary>
    void RollBack(Journal j)
    {
        var staging = Path.Combine(_parent, j.Staging);
        var aside = Path.Combine(_parent, j.Aside);
        foreach (var f in j.Files)
        {
            var dst = Path.Combine(Final, f);
            if (File.Exists(dst) && !File.Exists(Path.Combine(staging, f))) { try { File.Delete(dst); } catch (IOException) { } }
        }
        foreach (var f in j.Previous)
        {
            var src = Path.Combine(aside, f);
            if (File.Exists(src)) { try { File.Move(src, Path.Combine(Final, f)); } catch (IOException) { } }
        }
        TryDelete(aside);
        try { File.Delete(JournalPath); } catch (IOException) { }
    }

    /// <summary>A journal left by a run killed during its swap (we hold the lock, so its writer is gone): the swap finished.</summary>
    void Recover()
    {
        if (!File.Exists(JournalPath)) return;
        var j = Journal.Read(JournalPath, _name);
        int step = int.MinValue;   // no fault injection while finishing another run's swap
        Finish(j, ref step);
    }

    static void TryDelete(string dir)
    {
        try { if (Directory.Exists(dir) && !IsLink(dir)) Directory.Delete(dir, recursive: true); }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException) { }
    }

    static bool IsLink(string path) => new FileInfo(path).LinkTarget is not null;

    /// <summary>The top-level names the files go under must be real folders of the folder, not links or files.</summary>
    void CheckNames(IEnumerable<string> names, HashSet<string>? previous = null)
    {
        foreach (var name in names)
        {
            var p = Path.Combine(Final, name);
            if (IsLink(p))
                throw new InputException(p,
                    $"is a symbolic link to {MessageText.Quote(new FileInfo(p).LinkTarget, 80)}, not a folder of the {What}",
                    "remove the link or choose another -o: spectral never writes or removes through a link");
            if (name == "bands" && Manifest == RenderManifest.FileName && File.Exists(p) && previous?.Contains(name) != true)
                throw new InputException(p, "is a file where the render writes its bands/ folder", "move it away or choose another -o");
        }
    }

    /// <summary>
    /// The files the previous manifest lists, as relative paths inside the folder — only those that stay inside it:
    /// no absolute path, no "..", no component that is a symbolic link. A missing or unreadable manifest lists nothing.
    /// Outputs added into a folder: the command's own names.
    /// </summary>
    public HashSet<string> PreviousFiles()
    {
        var set = new HashSet<string>(StringComparer.Ordinal);
        if (_owned is not null)
        {
            foreach (var n in _owned) if (InsideFolder(n)) set.Add(n);
            return set;
        }
        var manifest = Path.Combine(Final, Manifest!);
        if (!File.Exists(manifest) || IsLink(manifest)) return set;
        try
        {
            var length = new FileInfo(manifest).Length;
            if (length > InputFile.MaxTextBytes) return set;
            if (JsonNode.Parse(File.ReadAllText(manifest)) is not JsonObject json || json["files"] is not JsonArray list) return set;
            set.Add(Manifest!);
            foreach (var n in list)
            {
                if (n is not JsonValue v || !v.TryGetValue<string>(out var f) || !InsideFolder(f)) continue;
                set.Add(f);
            }
        }
        catch (Exception e) when (e is JsonException or IOException or UnauthorizedAccessException or InvalidOperationException)
        {
            set.Clear();
        }
        return set;
    }

    bool InsideFolder(string relative)
    {
        if (!JsonFields.IsRelativeName(relative, out _)) return false;
        var parts = relative.Split('/');
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
            string? tag = rest.StartsWith(StagingTag, StringComparison.Ordinal)
                ? StagingTag
                : rest.StartsWith(AsideTag, StringComparison.Ordinal)
                ? AsideTag
                : null;
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

    /// <summary>A full path with every symbolic link along it resolved (as the kernel would), for the parts that exist.</summary>
    public static string RealPath(string fullPath)
    {
        var root = Path.GetPathRoot(fullPath) ?? "/";
        string current = root;
        int hops = 0;
        var pending =
            new Stack<string>(fullPath[root.Length..].Split(Path.DirectorySeparatorChar, StringSplitOptions.RemoveEmptyEntries).Reverse());
        while (pending.Count > 0)
        {
            var part = pending.Pop();
            if (part == ".") continue;
            if (part == "..") { current = Path.GetDirectoryName(current) ?? root; continue; }
            var next = Path.Combine(current, part);
            if (new FileInfo(next).LinkTarget is { } target)
            {
                if (++hops > 40) throw new IOException($"too many symbolic links in {fullPath}");
                foreach (var p in target.Split(Path.DirectorySeparatorChar, StringSplitOptions.RemoveEmptyEntries).Reverse())
                    pending.Push(p);
                if (Path.IsPathRooted(target)) current = root;
                continue;
            }
            current = next;
        }
        return current;
    }

    /// <summary>
    /// Whether two paths are the same folder by identity, not spelling: their real paths agree, or a file made in
    /// <paramref name="target"/> is seen in <paramref name="source"/> (another mount of the same folder).
    /// </summary>
    public static bool SameFolder(string source, string target)
    {
        if (!Directory.Exists(source) || !Directory.Exists(target)) return false;
        string a = RealPath(Path.GetFullPath(source).TrimEnd(Path.DirectorySeparatorChar));
        string b = RealPath(Path.GetFullPath(target).TrimEnd(Path.DirectorySeparatorChar));
        if (a == b) return true;
        var probe = $".spectral-identity-{Environment.ProcessId}-{Guid.NewGuid():N}";
        try
        {
            using (File.Create(Path.Combine(b, probe))) { }
            return File.Exists(Path.Combine(a, probe));
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException) { return false; }
        finally
        {
            try { File.Delete(Path.Combine(b, probe)); }
            catch (Exception e) when (e is IOException or UnauthorizedAccessException) { }
        }
    }

    /// <summary>The swap's journal: folder names beside the target, the manifest's name, the old and the new file names.</summary>
    sealed record Journal(string Staging, string Aside, string? Manifest, string[] Previous, string[] Files)
    {
        public string ToJson() => new JsonObject
        {
            ["staging"] = Staging,
            ["aside"] = Aside,
            ["manifest"] = Manifest,
            ["previous"] = new JsonArray(Previous.Select(f => (JsonNode)f).ToArray()),
            ["files"] = new JsonArray(Files.Select(f => (JsonNode)f).ToArray()),
        }.ToJsonString() + "\n";

        /// <summary>A journal read back and checked: its folders are this target's staging and aside, its names inside the
        /// folder.</summary>
        public static Journal Read(string path, string name)
        {
            var json = JsonFields.ParseFile(path, "swap journal", "");
            var r = new JsonFields(path, "move the journal away and check the folder by hand (a run killed during its swap left it)");
            string Folder(string key, string tag)
            {
                var v = r.String(json, key, "$");
                if (!v.StartsWith($".{name}{tag}", StringComparison.Ordinal) || !v.EndsWith(TmpSuffix, StringComparison.Ordinal)
                    || v.Contains('/'))
                    throw new InputException($"{path}: $.{key}",
                        $"{MessageText.Quote(v, 80)} is not this folder's {(tag == StagingTag ? "staging" : "aside")} folder",
                        "move the journal away and check the folder by hand");
                return v;
            }
            string[] Names(string key) => [.. (r.OptArray(json, key, "$") ?? []).Select((n, i) => r.RelativeName(n, $"$.{key}[{i}]"))];
            return new Journal(Folder("staging", StagingTag), Folder("aside", AsideTag), r.OptString(json, "manifest", "$"),
                Names("previous"), Names("files"));
        }
    }
}
