using System.Text.Json;

namespace SpectralRenderer.Scenes.Loading;

// "calculation_grids": work planes whose illuminance (lx) a render writes as grids/NAME.csv and grids/NAME.svg.
public sealed partial class SceneLoader
{
    List<CalculationGrid> ParseCalculationGrids(JsonElement root)
    {
        var grids = new List<CalculationGrid>();
        if (!TryGet(root, "calculation_grids", out var array)) return grids;
        if (array.ValueKind != JsonValueKind.Array)
            throw Error("$.calculation_grids", $"expected an array of grids, found {Kind(array)}",
                "e.g. \"calculation_grids\": [{\"name\": \"desk\", \"origin\": [0, 0.8, 0], \"u\": [2, 0, 0], \"v\": "
                    + "[0, 0, -1], \"points\": [8, 4]}]");
        if (array.GetArrayLength() > 0 && _radiometry != Radiometry.Physical)
            throw Error("$.calculation_grids",
                "a calculation grid gives illuminance in lx, which needs physical radiometry (eq. 2's paper units are relative)",
                "add \"radiometry\": \"physical\" to the scene");
        var names = new HashSet<string>(StringComparer.OrdinalIgnoreCase);
        int k = 0;
        foreach (var g in array.EnumerateArray())
        {
            string path = $"$.calculation_grids[{k}]";
            Object(g, path);
            Keys(g, path, "name", "origin", "u", "v", "points");
            string name = TryGet(g, "name", out var n) ? String(n, $"{path}.name") : $"grid{k + 1}";
            if (name.Length is 0 or > 64 || !name.All(c => char.IsAsciiLetterOrDigit(c) || c is '-' or '_'))
                throw Error($"{path}.name", $"'{name}' is not a file name of letters, digits, '-' and '_' (1 to 64)",
                    "e.g. \"desk-1\": it names grids/NAME.csv and grids/NAME.svg");
            if (!names.Add(name))
                throw Error($"{path}.name", $"two calculation grids are named '{name}'",
                    "give each grid its own name (it names its files)");
            var origin = Vec3(Required(g, "origin", path), $"{path}.origin");
            var u = Vec3(Required(g, "u", path), $"{path}.u");
            var v = Vec3(Required(g, "v", path), $"{path}.v");
            if (!(System.Numerics.Vector3.Cross(u, v).Length() > 1e-9f))
                throw Error($"{path}.v", "the edge vectors u and v are parallel (or zero)",
                    "give two edges that span the work plane, e.g. u [2, 0, 0] and v [0, 0, -1]");
            var points = Required(g, "points", path);
            if (points.ValueKind != JsonValueKind.Array || points.GetArrayLength() != 2 ||
                !Whole(points[0], out int nu) || !Whole(points[1], out int nv) ||
                nu is < 1 or > CalculationGrid.MaxPoints || nv is < 1 or > CalculationGrid.MaxPoints)
                throw Error($"{path}.points",
                    $"expected [NU, NV], two whole numbers from 1 to {CalculationGrid.MaxPoints}, found "
                        + $"{(points.ValueKind == JsonValueKind.Array ? points.GetRawText() : Kind(points))}",
                    "e.g. [8, 4]: the grid points along u and along v");
            grids.Add(new CalculationGrid(name, origin, u, v, nu, nv));
            k++;
        }
        return grids;
    }

    static bool Whole(JsonElement e, out int value)
    {
        value = 0;
        return e.ValueKind == JsonValueKind.Number && e.TryGetInt32(out value);
    }
}
