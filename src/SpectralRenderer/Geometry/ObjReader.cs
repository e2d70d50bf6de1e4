using System.Globalization;
using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Geometry;

/// <summary>
/// Reads the geometry of a Wavefront OBJ file: <c>v</c>, <c>vn</c> and <c>f</c> (corners <c>v</c>, <c>v/vt</c>,
/// <c>v//vn</c>, <c>v/vt/vn</c>; negative indices count back from the last element read; polygons are
/// fan-triangulated). Every other keyword (<c>vt</c>, <c>g</c>, <c>o</c>, <c>s</c>, <c>mtllib</c>, ...) is ignored.
/// A vertex gets the file's normal when all corners using it name the same <c>vn</c>; otherwise the mesh's
/// normals are computed. Errors name "file:line".
/// </summary>
public static class ObjReader
{
    public static TriangleMesh Read(string path)
    {
        return Parse(InputFile.ReadAllText(path), path);
    }

    public static TriangleMesh Parse(TextReader reader, string path) => Parse(reader.ReadToEnd(), path);

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static TriangleMesh Parse(ReadOnlySpan<char> text, string path)
    {
        var positions = new List<Vector3>();
        var normals = new List<Vector3>();
        var indices = new List<int>();
        var cornerNormals = new List<int>(); // vn index (0-based) per corner of `indices`, -1 when none
        int texCoordCount = 0, faceCount = 0;
        Span<int> vertex = stackalloc int[3];   // the fan's first and previous corner: position and normal
        Span<int> normal = stackalloc int[3];

        int lineNumber = 0;
        while (text.Length > 0)
        {
            lineNumber++;
            int eol = text.IndexOf('\n');
            var line = eol < 0 ? text : text[..eol];
            text = eol < 0 ? [] : text[(eol + 1)..];
            int hash = line.IndexOf('#');
            if (hash >= 0) line = line[..hash];

            var tokens = new Tokens(line);
            var keyword = tokens.Next();
            if (keyword.Length == 0) continue;
            if (keyword.SequenceEqual("v"))
                positions.Add(ReadVector(ref tokens, path, lineNumber, "v"));
            else if (keyword.SequenceEqual("vn"))
                normals.Add(ReadVector(ref tokens, path, lineNumber, "vn"));
            else if (keyword.SequenceEqual("vt"))
                texCoordCount++;
            else if (keyword.SequenceEqual("f"))
            {
                int corners = 0;
                for (var corner = tokens.Next(); corner.Length > 0; corner = tokens.Next(), corners++)
                {
                    var (p, n) = ReadCorner(corner, positions.Count, texCoordCount, normals.Count, path, lineNumber);
                    if (corners < 2) { vertex[corners] = p; normal[corners] = n; continue; }
                    // Fan: (first, previous, this).
                    indices.Add(vertex[0]); indices.Add(vertex[1]); indices.Add(p);
                    cornerNormals.Add(normal[0]); cornerNormals.Add(normal[1]); cornerNormals.Add(n);
                    vertex[1] = p; normal[1] = n;
                }
                if (corners < 3)
                    throw new InputException($"{path}:{lineNumber}", $"face has {corners} vertices (a face needs at least 3)");
                faceCount++;
            }
        }
        if (faceCount == 0) throw new InputException(path, "no faces (empty mesh)", "the file must contain 'f' lines");

        var positionArray = positions.ToArray();
        var mapped = MapNormals(positionArray.Length, indices, cornerNormals, normals);
        var mesh = new TriangleMesh(positionArray, indices.ToArray(), mapped, path);
        if (mesh.TriangleCount == 0)
            throw new InputException(path, $"all {mesh.DegenerateCount} triangles are degenerate (zero area)");
        if (mesh.Normals is null) mesh.ComputeVertexNormals();
        return mesh;
    }

    /// <summary>Per-vertex normals from per-corner ones, or null when some vertex has none or several.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static Vector3[]? MapNormals(int vertexCount, List<int> indices, List<int> cornerNormals, List<Vector3> normals)
    {
        if (normals.Count == 0) return null;
        var chosen = new int[vertexCount];
        Array.Fill(chosen, -1);
        for (int i = 0; i < indices.Count; i++)
        {
            int n = cornerNormals[i];
            if (n < 0) return null;
            ref int c = ref chosen[indices[i]];
            if (c < 0) c = n;
            else if (c != n && normals[c] != normals[n]) return null;
        }
        var result = new Vector3[vertexCount];
        for (int v = 0; v < vertexCount; v++)
        {
            if (chosen[v] < 0) { result[v] = Vector3.UnitZ; continue; }
            var n = normals[chosen[v]];
            float len = n.Length();
            result[v] = len > 0 && float.IsFinite(len) ? n / len : Vector3.UnitZ;
        }
        return result;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static Vector3 ReadVector(ref Tokens tokens, string path, int line, string keyword)
    {
        float x = ReadFloat(ref tokens, path, line, keyword);
        float y = ReadFloat(ref tokens, path, line, keyword);
        float z = ReadFloat(ref tokens, path, line, keyword);
        return new Vector3(x, y, z); // extra values (w, vertex colours) are ignored
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static float ReadFloat(ref Tokens tokens, string path, int line, string keyword)
    {
        var token = tokens.Next();
        if (token.Length == 0)
            throw new InputException($"{path}:{line}", $"'{keyword}' needs 3 coordinates x y z");
        if (!float.TryParse(token, NumberStyles.Float, CultureInfo.InvariantCulture, out float value) || !float.IsFinite(value))
            throw new InputException($"{path}:{line}", $"coordinate '{token}' is not a finite number");
        return value;
    }

    /// <summary>One face corner "v[/[vt][/vn]]" as 0-based (position, normal or -1).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static (int position, int normal) ReadCorner(ReadOnlySpan<char> corner, int positions, int texCoords, int normals,
        string path, int line)
    {
        int slash = corner.IndexOf('/');
        int p = Resolve(slash < 0 ? corner : corner[..slash], positions, "vertex", path, line);
        if (slash < 0) return (p, -1);
        var rest = corner[(slash + 1)..];
        slash = rest.IndexOf('/');
        var vt = slash < 0 ? rest : rest[..slash];
        if (vt.Length > 0) Resolve(vt, texCoords, "texture coordinate", path, line);
        if (slash < 0 || slash == rest.Length - 1) return (p, -1);
        return (p, Resolve(rest[(slash + 1)..], normals, "normal", path, line));
    }

    /// <summary>A 1-based (or negative, relative) OBJ index to a 0-based one, checked against what is defined so far.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static int Resolve(ReadOnlySpan<char> token, int count, string what, string path, int line)
    {
        if (!int.TryParse(token, NumberStyles.AllowLeadingSign, CultureInfo.InvariantCulture, out int index))
            throw new InputException($"{path}:{line}", $"{what} index '{token}' is not an integer");
        int resolved = index > 0 ? index - 1 : count + index;
        if (index == 0 || resolved < 0 || resolved >= count)
            throw new InputException($"{path}:{line}", $"{what} index {index} out of range ({count} defined so far)",
                index == 0 ? "OBJ indices start at 1; negative ones count back from the last" : null);
        return resolved;
    }

    /// <summary>Whitespace-separated tokens of one line, as spans (no allocation).</summary>
    ref struct Tokens(ReadOnlySpan<char> line)
    {
        ReadOnlySpan<char> _rest = line;

        [MethodImpl(MethodImplOptions.AggressiveOptimization)]
        public ReadOnlySpan<char> Next()
        {
            int i = 0;
            while (i < _rest.Length && char.IsWhiteSpace(_rest[i])) i++;
            int start = i;
            while (i < _rest.Length && !char.IsWhiteSpace(_rest[i])) i++;
            var token = _rest[start..i];
            _rest = _rest[i..];
            return token;
        }
    }
}
