using System.Globalization;
using System.Numerics;
using System.Text.Json;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Loading;

// The JSON readers of the loader: each value read with its JSON path, every error located at file:line:column.
public sealed partial class SceneLoader
{
    InputException Error(string jsonPath, string what, string hint, InputProblem problem = InputProblem.Invalid)
    {
        // Point at the nearest located ancestor when the path itself is absent (a missing field).
        string p = jsonPath;
        string? pos = _locator.Locate(p);
        while (pos is null && p.Length > 1)
        {
            int cut = Math.Max(p.LastIndexOf('.'), p.LastIndexOf('['));
            if (cut <= 0) break;
            p = p[..cut];
            pos = _locator.Locate(p);
        }
        return new InputException(pos is null ? $"{_file}: {jsonPath}" : $"{_file}:{pos}: {jsonPath}", what, hint) { Problem = problem };
    }

    static string Kind(JsonElement e) => e.ValueKind switch
    {
        JsonValueKind.Object => "an object",
        JsonValueKind.Array => "an array",
        JsonValueKind.String => "a string",
        JsonValueKind.Number => "a number",
        JsonValueKind.True or JsonValueKind.False => "a boolean",
        _ => "null",
    };

    void Keys(JsonElement obj, string path, params string[] allowed)
    {
        foreach (var p in obj.EnumerateObject())
            if (Array.IndexOf(allowed, p.Name) < 0)
                throw Error($"{path}.{p.Name}", $"unknown field {MessageText.Quote(p.Name)}",
                    InputException.DidYouMean(p.Name, allowed) ?? $"allowed here: {string.Join(", ", allowed)}");
    }

    JsonElement Object(JsonElement e, string path)
    {
        if (e.ValueKind != JsonValueKind.Object)
            throw Error(path, $"expected an object, found {Kind(e)}", "write it as { \"key\": value, … }");
        return e;
    }

    static bool TryGet(JsonElement obj, string name, out JsonElement value) =>
        obj.TryGetProperty(name, out value) && value.ValueKind != JsonValueKind.Null;

    JsonElement Required(JsonElement obj, string name, string path)
    {
        if (!TryGet(obj, name, out var v))
            throw Error($"{path}.{name}", $"missing required field '{name}'", "see docs/scene-format.md for the required fields");
        return v;
    }

    double Number(JsonElement e, string path, double min = -MaxMagnitude, double max = MaxMagnitude)
    {
        if (e.ValueKind != JsonValueKind.Number)
            throw Error(path, $"expected a number, found {Kind(e)}", "write a plain number such as 1.5");
        double v = e.GetDouble();
        min = Math.Max(min, -MaxMagnitude);
        max = Math.Min(max, MaxMagnitude);
        if (!double.IsFinite(v) || v < min || v > max)
            throw Error(path, $"{v.ToString(CultureInfo.InvariantCulture)} is out of range",
                $"expected {min.ToString(CultureInfo.InvariantCulture)} to {max.ToString(CultureInfo.InvariantCulture)}");
        return v;
    }

    double Number(JsonElement obj, string name, string path, double fallback, double min = -MaxMagnitude, double max = MaxMagnitude) =>
        TryGet(obj, name, out var v) ? Number(v, $"{path}.{name}", min, max) : fallback;

    int Integer(JsonElement obj, string name, string path, int fallback, int min, int max)
    {
        if (!TryGet(obj, name, out var v)) return fallback;
        if (v.ValueKind != JsonValueKind.Number || !v.TryGetInt32(out int i))
            throw Error($"{path}.{name}",
                $"expected a whole number, found {(v.ValueKind == JsonValueKind.Number ? v.GetRawText() : Kind(v))}",
                "write an integer such as 4");
        if (i < min || i > max) throw Error($"{path}.{name}", $"{i} is out of range", $"expected {min} to {max}");
        return i;
    }

    string String(JsonElement e, string path)
    {
        if (e.ValueKind != JsonValueKind.String) throw Error(path, $"expected a string, found {Kind(e)}", "write it in double quotes");
        return e.GetString()!;
    }

    bool Bool(JsonElement obj, string name, string path, bool fallback)
    {
        if (!TryGet(obj, name, out var v)) return fallback;
        if (v.ValueKind is not (JsonValueKind.True or JsonValueKind.False))
            throw Error($"{path}.{name}", $"expected true or false, found {Kind(v)}", "write true or false without quotes");
        return v.GetBoolean();
    }

    Vector3 Vec3(JsonElement obj, string name, string path, Vector3 fallback)
    {
        if (!TryGet(obj, name, out var v)) return fallback;
        return Vec3(v, $"{path}.{name}");
    }

    Vector3 Vec3(JsonElement v, string path)
    {
        if (v.ValueKind != JsonValueKind.Array || v.GetArrayLength() != 3)
            throw Error(path, $"expected [x, y, z], found {Kind(v)}", "e.g. [0, 1, 5]");
        return new Vector3((float)Number(v[0], $"{path}[0]", -MaxCoordinate, MaxCoordinate),
            (float)Number(v[1], $"{path}[1]", -MaxCoordinate, MaxCoordinate),
            (float)Number(v[2], $"{path}[2]", -MaxCoordinate, MaxCoordinate));
    }

    Vector3 Direction(JsonElement e, string path)
    {
        var v = Vec3(e, path);
        if (v.LengthSquared() == 0) throw Error(path, "the direction is the zero vector", "give a non-zero direction such as [0, -1, 0]");
        return Vector3.Normalize(v);
    }
}
