using System.Globalization;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Pbrt;

/// <summary>
/// One parameter of a pbrt directive, `"type name" value` or `"type name" [ values ]`: numbers for the numeric types
/// (float, integer, point2/3, vector2/3, normal, rgb, blackbody, and spectrum given as λ v pairs), strings for
/// string, texture and a named or file spectrum, booleans for bool. <see cref="Used"/> is set when the importer reads it.
/// </summary>
public sealed class PbrtParameter
{
    public required string Type { get; init; }
    public required string Name { get; init; }
    public required PbrtToken Token { get; init; }
    public double[] Numbers { get; init; } = [];
    public string[] Strings { get; init; } = [];
    public bool[] Bools { get; init; } = [];
    public bool Used { get; set; }

    public string Where => Token.Where;
}

/// <summary>The parameter list of one directive, read by name with pbrt-v4's defaults; unread ones are reported.</summary>
public sealed class PbrtParameters
{
    static readonly string[] NumericTypes =
        ["float", "integer", "point", "point2", "point3", "vector", "vector2", "vector3", "normal", "normal3", "rgb", "color",
            "blackbody"];

    readonly List<PbrtParameter> _list;

    public PbrtParameters(List<PbrtParameter> list) => _list = list;

    public IReadOnlyList<PbrtParameter> All => _list;

    public PbrtParameter? Find(string name)
    {
        PbrtParameter? found = null;
        foreach (var p in _list)
            if (p.Name == name) found = p;   // the last one wins, as in pbrt
        if (found is not null) found.Used = true;
        return found;
    }

    /// <summary>Whether the list names <paramref name="name"/> (without marking it read).</summary>
    public bool Has(string name) => _list.Exists(p => p.Name == name);

    public double Float(string name, double fallback)
    {
        var p = Find(name);
        if (p is null) return fallback;
        if (p.Type is not ("float" or "integer") || p.Numbers.Length != 1)
            throw new InputException(p.Where, $"\"{p.Type} {p.Name}\" should be one float", $"e.g. \"float {name}\" {Format(fallback)}");
        return p.Numbers[0];
    }

    public int Integer(string name, int fallback)
    {
        var p = Find(name);
        if (p is null) return fallback;
        if (p.Type != "integer" || p.Numbers.Length != 1 || p.Numbers[0] != Math.Round(p.Numbers[0])
            || Math.Abs(p.Numbers[0]) > int.MaxValue)
            throw new InputException(p.Where, $"\"{p.Type} {p.Name}\" should be one integer", $"e.g. \"integer {name}\" {fallback}");
        return (int)p.Numbers[0];
    }

    public bool Bool(string name, bool fallback)
    {
        var p = Find(name);
        if (p is null) return fallback;
        if (p.Type != "bool" || p.Bools.Length != 1)
            throw new InputException(p.Where, $"\"{p.Type} {p.Name}\" should be one bool", $"e.g. \"bool {name}\" true");
        return p.Bools[0];
    }

    public string? String(string name)
    {
        var p = Find(name);
        if (p is null) return null;
        if (p.Type != "string" || p.Strings.Length != 1)
            throw new InputException(p.Where, $"\"{p.Type} {p.Name}\" should be one string", $"e.g. \"string {name}\" \"…\"");
        return p.Strings[0];
    }

    /// <summary>A numeric array of a multiple of <paramref name="arity"/> values of one of the types given, or null.</summary>
    public double[]? Numbers(string name, int arity, params string[] types)
    {
        var p = Find(name);
        if (p is null) return null;
        if (Array.IndexOf(types, p.Type) < 0 || p.Numbers.Length == 0 || p.Numbers.Length % arity != 0)
            throw new InputException(p.Where,
                $"\"{p.Type} {p.Name}\" should be {(arity == 1 ? "numbers" : $"groups of {arity} numbers")} of "
                    + $"type {string.Join(" or ", types)}",
                $"e.g. \"{types[0]} {name}\" [ {string.Join(" ", Enumerable.Repeat("0", arity))} ]");
        return p.Numbers;
    }

    public static bool IsNumeric(string type) => Array.IndexOf(NumericTypes, type) >= 0;

    static string Format(double v) => v.ToString("R", CultureInfo.InvariantCulture);
}
