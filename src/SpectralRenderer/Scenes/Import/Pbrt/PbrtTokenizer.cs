using System.Globalization;
using System.Text;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Pbrt;

/// <summary>What a pbrt token is: a quoted string, a bare word (a directive, a number, true/false) or a bracket.</summary>
public enum PbrtTokenKind { String, Word, OpenBracket, CloseBracket }

/// <summary>One token of a pbrt-v4 file with the place it starts (file, 1-based line and column).</summary>
public readonly record struct PbrtToken(PbrtTokenKind Kind, string Text, string File, int Line, int Column)
{
    public string Where => $"{File}:{Line}:{Column}";

    public bool IsNumber => Kind == PbrtTokenKind.Word && TryNumber(out _);

    public bool TryNumber(out double value) =>
        double.TryParse(Text, NumberStyles.Float, CultureInfo.InvariantCulture, out value) && double.IsFinite(value);

    /// <summary>How the token reads in a message: a string in quotes, a word as it is, shortened and escaped.</summary>
    public string Quoted => Kind == PbrtTokenKind.String ? MessageText.Quote("\"" + Text + "\"") : MessageText.Quote(Text);
}

/// <summary>
/// The lexical grammar of pbrt-v4's scene files (pbrt.org/fileformat-v4): whitespace separates tokens, `#` starts a
/// comment to the end of the line, strings are in double quotes (with the escapes \n \t \\ \" and \b \f \r), `[` and `]`
/// are tokens of their own, and anything else up to whitespace, a quote, a bracket or a comment is a word.
/// </summary>
public static class PbrtTokenizer
{
    /// <summary>The longest string token (a longer one is a missing quote).</summary>
    const int MaxStringLength = 1 << 20;

    public static List<PbrtToken> Tokenize(string text, string file)
    {
        var tokens = new List<PbrtToken>();
        int i = 0, line = 1, lineStart = 0;
        while (i < text.Length)
        {
            char c = text[i];
            if (c == '\n') { i++; line++; lineStart = i; continue; }
            if (char.IsWhiteSpace(c) || c == '\uFEFF') { i++; continue; }
            int column = i - lineStart + 1;
            if (c == '#')
            {
                while (i < text.Length && text[i] != '\n') i++;
                continue;
            }
            if (c == '[' || c == ']')
            {
                tokens.Add(new(c == '[' ? PbrtTokenKind.OpenBracket : PbrtTokenKind.CloseBracket, c.ToString(), file, line, column));
                i++;
                continue;
            }
            if (c == '"')
            {
                var sb = new StringBuilder();
                int startLine = line;
                i++;
                while (true)
                {
                    if (i >= text.Length || text[i] == '\n')
                        throw new InputException($"{file}:{startLine}:{column}", "a string is not closed before the end of the line",
                            "close it with a double quote (\")");
                    char s = text[i++];
                    if (s == '"') break;
                    if (s == '\\')
                    {
                        if (i >= text.Length)
                            throw new InputException($"{file}:{line}:{i - lineStart}", "a backslash ends the file", "remove it");
                        char e = text[i++];
                        sb.Append(e switch
                        {
                            'n' => '\n',
                            't' => '\t',
                            'r' => '\r',
                            'b' => '\b',
                            'f' => '\f',
                            '\\' or '"' or '\'' => e,
                            _ => throw new InputException($"{file}:{line}:{i - lineStart - 1}",
                                $"unknown escape \\{MessageText.Escape(e.ToString())} in a string", "write \\\\ for a backslash"),
                        });
                    }
                    else sb.Append(s);
                    if (sb.Length > MaxStringLength)
                        throw new InputException($"{file}:{startLine}:{column}", "a string is longer than 1 MiB", "is a quote missing?");
                }
                tokens.Add(new(PbrtTokenKind.String, sb.ToString(), file, startLine, column));
                continue;
            }
            int start = i;
            while (i < text.Length && !char.IsWhiteSpace(text[i]) && text[i] is not ('"' or '[' or ']' or '#')) i++;
            tokens.Add(new(PbrtTokenKind.Word, text[start..i], file, line, column));
        }
        return tokens;
    }
}
