using System.Globalization;
using System.Text;

namespace SpectralRenderer.Diagnostics;

/// <summary>
/// Makes text from the user (names, paths, tokens of a file) safe to print on one terminal line: control
/// characters, ANSI escapes, NUL and other non-printable code points are written as \n, \t, \e, \0 or \u{XXXX};
/// a long piece is cut in the middle with "…". Every message the tool prints goes through <see cref="Line"/>.
/// </summary>
public static class MessageText
{
    /// <summary>The longest message line, in characters (a screen line or three).</summary>
    public const int MaxLine = 300;

    /// <summary>The longest quoted token ('…' of a file's content), in characters.</summary>
    public const int MaxToken = 40;

    /// <summary>A token from the input, escaped and cut to <paramref name="max"/> characters, in single quotes.</summary>
    public static string Quote(string? token, int max = MaxToken) => $"'{Shorten(Escape(token ?? ""), max)}'";

    /// <summary>A token from the input as bytes (decoded as UTF-8, invalid bytes as \xNN), escaped and quoted.</summary>
    public static string Quote(ReadOnlySpan<byte> token, int max = MaxToken)
    {
        var sb = new StringBuilder();
        int limit = Math.Min(token.Length, 4 * max);
        var part = token[..limit];
        while (part.Length > 0)
        {
            var status = System.Text.Rune.DecodeFromUtf8(part, out var rune, out int used);
            if (status == System.Buffers.OperationStatus.Done) sb.Append(rune.ToString());
            else sb.Append('\uFFFD');
            part = part[Math.Max(used, 1)..];
        }
        if (limit < token.Length) sb.Append('…');
        return Quote(sb.ToString(), max);
    }

    /// <summary>Escapes every character that is not printable on one line.</summary>
    public static string Escape(string s)
    {
        bool clean = true;
        foreach (char c in s) if (!Printable(c)) { clean = false; break; }
        if (clean) return s;
        var sb = new StringBuilder(s.Length + 8);
        for (int i = 0; i < s.Length; i++)
        {
            char c = s[i];
            if (char.IsHighSurrogate(c) && i + 1 < s.Length && char.IsLowSurrogate(s[i + 1])) { sb.Append(c).Append(s[++i]); continue; }
            if (Printable(c)) { sb.Append(c); continue; }
            sb.Append(c switch
            {
                '\n' => "\\n",
                '\r' => "\\r",
                '\t' => "\\t",
                '\0' => "\\0",
                '\x1b' => "\\e",
                _ => string.Create(CultureInfo.InvariantCulture, $"\\u{{{(int)c:X4}}}"),
            });
        }
        return sb.ToString();
    }

    static bool Printable(char c)
    {
        if (c < 0x20 || c == 0x7F) return false;
        if (c < 0x7F) return true;
        var cat = char.GetUnicodeCategory(c);
        return cat is not (UnicodeCategory.Control or UnicodeCategory.Format or UnicodeCategory.LineSeparator
            or UnicodeCategory.ParagraphSeparator or UnicodeCategory.Surrogate or UnicodeCategory.OtherNotAssigned
            or UnicodeCategory.PrivateUse);
    }

    /// <summary>Cuts <paramref name="s"/> to at most <paramref name="max"/> characters, keeping its start and end around "…".</summary>
    public static string Shorten(string s, int max)
    {
        if (s.Length <= max) return s;
        if (max < 8) return s[..Math.Max(0, max - 1)] + "…";
        int head = (max - 1) * 2 / 3, tail = max - 1 - head;
        if (char.IsHighSurrogate(s[head - 1])) head--;
        if (char.IsLowSurrogate(s[^tail])) tail--;
        return s[..head] + "…" + s[^tail..];
    }

    /// <summary>
    /// The one line of a bad input, "where: what (hint: hint)", at most <see cref="MaxLine"/> characters. What is
    /// wrong is cut last: first the place loses its beginning (a long folder path, keeping the file name, line:column
    /// and JSON path at its end), then the hint is cut in the middle, and only then the reason itself.
    /// </summary>
    public static string Problem(string where, string what, string? hint)
    {
        string w = Escape(where), r = Escape(what), h = string.IsNullOrEmpty(hint) ? "" : Escape(hint);
        string Join() => (w.Length > 0 ? w + ": " : "") + r + (h.Length > 0 ? " (hint: " + h + ")" : "");
        int Excess() => Join().Length - MaxLine;
        if (Excess() > 0) w = ShortenFolder(w, Excess());
        if (Excess() > 0 && w.Length > MaxPlace) w = Shorten(w, MaxPlace);   // a file name or JSON path longer than a line
        if (Excess() > 0 && h.Length > MinHint) h = Shorten(h, Math.Max(MinHint, h.Length - Excess()));
        if (Excess() > 0) r = Shorten(r, Math.Max(12, r.Length - Excess()));
        return Join();
    }

    /// <summary>The longest a place keeps after its folder is gone, and the shortest a hint is cut to, before the reason is cut.</summary>
    const int MaxPlace = 150, MinHint = 40;

    /// <summary>
    /// A place "folder/file:line:column: $.json.path" with its folder cut by <paramref name="excess"/> characters from
    /// the start ("…" + the folder's end), keeping the file's name and everything after it.
    /// </summary>
    static string ShortenFolder(string place, int excess)
    {
        int colon = place.IndexOf(':');
        int slash = place.LastIndexOf('/', colon < 0 ? place.Length - 1 : colon);
        if (slash <= 1) return place;
        int keep = Math.Max(0, slash - excess - 1);
        if (keep > 0 && char.IsLowSurrogate(place[slash - keep])) keep--;
        return "…" + place[(slash - keep)..];
    }

    /// <summary>
    /// One printable line of at most <see cref="MaxLine"/> characters from its parts: each escaped, and the
    /// longest cut in the middle until the whole fits.
    /// </summary>
    public static string Line(params string[] parts)
    {
        var p = new string[parts.Length];
        for (int i = 0; i < parts.Length; i++) p[i] = Escape(parts[i]);
        while (p.Sum(x => x.Length) > MaxLine)
        {
            int longest = 0;
            for (int i = 1; i < p.Length; i++) if (p[i].Length > p[longest].Length) longest = i;
            int excess = p.Sum(x => x.Length) - MaxLine;
            int target = Math.Max(12, p[longest].Length - excess);
            if (target >= p[longest].Length) break;
            p[longest] = Shorten(p[longest], target);
        }
        return string.Concat(p);
    }
}
