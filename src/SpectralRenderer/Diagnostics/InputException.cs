namespace SpectralRenderer.Diagnostics;

/// <summary>What kind of bad input an <see cref="InputException"/> reports, for callers that treat kinds differently.</summary>
public enum InputProblem
{
    /// <summary>The input is there but wrong.</summary>
    Invalid,
    /// <summary>A file the input names (a scene, a mesh) does not exist.</summary>
    MissingFile,
}

/// <summary>
/// Bad input from the user (a file, a name, an argument). Its message is one line:
/// "where: what is wrong (hint: what to do)", made printable and at most <see cref="MessageText.MaxLine"/>
/// characters by <see cref="MessageText.Problem"/> (the reason cut last). Every bad input names its place and carries a hint.
/// The CLI prints it and exits with code 2.
/// </summary>
public sealed class InputException : Exception
{
    public InputException(string where, string what, string hint)
        : base(Format(where, what, hint))
    {
        Where = where;
        What = what;
        Hint = hint;
    }

    public string Where { get; }
    public string What { get; }
    public string Hint { get; }
    public InputProblem Problem { get; init; } = InputProblem.Invalid;

    static string Format(string where, string what, string? hint) => MessageText.Problem(where, what, hint);

    /// <summary>Suggests the closest known name ("did you mean 'green'?") by edit distance.</summary>
    public static string? DidYouMean(string name, IEnumerable<string> known)
    {
        string? best = null;
        int bestDistance = int.MaxValue;
        foreach (var k in known)
        {
            int d = Levenshtein(name.ToLowerInvariant(), k.ToLowerInvariant());
            if (d < bestDistance) { bestDistance = d; best = k; }
        }
        if (best is null) return null;
        return bestDistance <= Math.Max(2, name.Length / 3) ? $"did you mean '{best}'?" : null;
    }

    static int Levenshtein(string a, string b)
    {
        var prev = new int[b.Length + 1];
        var cur = new int[b.Length + 1];
        for (int j = 0; j <= b.Length; j++) prev[j] = j;
        for (int i = 1; i <= a.Length; i++)
        {
            cur[0] = i;
            for (int j = 1; j <= b.Length; j++)
                cur[j] = Math.Min(Math.Min(cur[j - 1] + 1, prev[j] + 1), prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1));
            (prev, cur) = (cur, prev);
        }
        return prev[b.Length];
    }
}
