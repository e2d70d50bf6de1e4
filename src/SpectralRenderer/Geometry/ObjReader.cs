using System.Globalization;
using System.Numerics;
using System.Runtime.CompilerServices;
using System.Text;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Geometry;

/// <summary>
/// Reads the geometry of a Wavefront OBJ file: <c>v</c>, <c>vn</c> and <c>f</c> (corners <c>v</c>, <c>v/vt</c>,
/// <c>v//vn</c>, <c>v/vt/vn</c>; negative indices count back from the last element read; polygons are
/// fan-triangulated), and <c>vt</c> (u v, kept per triangle corner when every corner names one). Every other keyword (<c>g</c>, <c>o</c>,
/// <c>s</c>, <c>mtllib</c>, ...) is ignored. A vertex gets the file's normal when all corners using it name the same <c>vn</c>; otherwise
/// the mesh's normals are computed. The file is parsed as UTF-8 bytes; numbers read exactly as float.Parse and int.Parse
/// read them. Errors name "file:line".
/// </summary>
public static class ObjReader
{
    public static TriangleMesh Read(string path)
    {
        var data = InputFile.ReadAllBytes(path, "mesh file");
        // A UTF-16 or UTF-32 file (by its byte order mark) is decoded as File.ReadAllText would.
        var start = data.AsSpan();
        if (start.StartsWith((ReadOnlySpan<byte>)[0xFE, 0xFF]) || start.StartsWith((ReadOnlySpan<byte>)[0xFF, 0xFE])
            || start.StartsWith((ReadOnlySpan<byte>)[0, 0, 0xFE, 0xFF]))
            data = Encoding.UTF8.GetBytes(new StreamReader(new MemoryStream(data), Encoding.UTF8, true).ReadToEnd());
        return Parse(data, path);
    }

    public static TriangleMesh Parse(TextReader reader, string path) => Parse(reader.ReadToEnd(), path);

    public static TriangleMesh Parse(ReadOnlySpan<char> text, string path)
    {
        var data = new byte[Encoding.UTF8.GetByteCount(text)];
        Encoding.UTF8.GetBytes(text, data);
        return Parse(data, path);
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static TriangleMesh Parse(ReadOnlySpan<byte> text, string path)
    {
        if (text.StartsWith("\uFEFF"u8)) text = text[3..]; // UTF-8 byte order mark
        // Growing arrays, first sized for a typical scan (~65 bytes of file per vertex, two triangles per vertex).
        int guess = text.Length / 64 + 16;
        var positions = new Vector3[guess];
        var normals = Array.Empty<Vector3>();
        var indices = new int[6 * guess];
        var cornerNormals = new int[6 * guess]; // vn index (0-based) per corner of `indices`, -1 when none
        var cornerTexCoords = new int[6 * guess]; // vt index (0-based) per corner of `indices`, -1 when none
        var texCoords = Array.Empty<Vector2>();
        int positionCount = 0, normalCount = 0, indexCount = 0, texCoordCount = 0, faceCount = 0;

        int lineNumber = 0;
        while (text.Length > 0)
        {
            lineNumber++;
            int eol = text.IndexOf((byte)'\n');
            var line = eol < 0 ? text : text[..eol];
            text = eol < 0 ? default : text[(eol + 1)..];
            int hash = line.IndexOf((byte)'#');
            if (hash >= 0) line = line[..hash];
            if (line.ContainsAnyExceptInRange((byte)0, (byte)0x7F)) line = SpacesToAscii(line);

            var tokens = new Tokens(line);
            var keyword = tokens.Next();
            if (keyword.Length == 0) continue;
            if (keyword.SequenceEqual("v"u8) || keyword.SequenceEqual("vn"u8))
            {
                bool isPosition = keyword.Length == 1;
                var name = isPosition ? "v" : "vn";
                float x = ReadFloat(ref tokens, path, lineNumber, name);
                float y = ReadFloat(ref tokens, path, lineNumber, name);
                float z = ReadFloat(ref tokens, path, lineNumber, name);
                // Extra values (w, vertex colours) are ignored.
                if (isPosition)
                {
                    if (positionCount == positions.Length) Array.Resize(ref positions, 2 * positions.Length);
                    positions[positionCount++] = new Vector3(x, y, z);
                }
                else
                {
                    if (normalCount == normals.Length) Array.Resize(ref normals, Math.Max(2 * normals.Length, guess));
                    normals[normalCount++] = new Vector3(x, y, z);
                }
            }
            else if (keyword.SequenceEqual("vt"u8))
            {
                float u = ReadFloat(ref tokens, path, lineNumber, "vt");
                var second = tokens.Next();   // v is optional (1D textures): 0
                float v = second.Length == 0 ? 0 : TryParseFloat(second, out float vv) && float.IsFinite(vv) ? vv
                    : throw new InputException($"{path}:{lineNumber}", $"vt: {MessageText.Quote(second)} is not a number",
                        "write vt u v with finite numbers");
                if (texCoordCount == texCoords.Length) Array.Resize(ref texCoords, Math.Max(2 * texCoords.Length, guess));
                texCoords[texCoordCount++] = new Vector2(u, v);
            }
            else if (keyword.SequenceEqual("f"u8))
            {
                int corners = 0, firstVertex = 0, firstNormal = 0, previousVertex = 0, previousNormal = 0, firstUv = 0, previousUv = 0;
                for (var corner = tokens.Next(); corner.Length > 0; corner = tokens.Next(), corners++)
                {
                    var (p, n, t) = ReadCorner(corner, positionCount, texCoordCount, normalCount, path, lineNumber);
                    if (corners == 0) (firstVertex, firstNormal, firstUv) = (p, n, t);
                    if (corners >= 2)
                    {
                        // Fan: (first, previous, this).
                        if (indexCount + 3 > indices.Length)
                        {
                            Array.Resize(ref indices, 2 * indices.Length);
                            Array.Resize(ref cornerNormals, indices.Length);
                            Array.Resize(ref cornerTexCoords, indices.Length);
                        }
                        cornerTexCoords[indexCount] = firstUv;
                        cornerTexCoords[indexCount + 1] = previousUv;
                        cornerTexCoords[indexCount + 2] = t;
                        indices[indexCount] = firstVertex; indices[indexCount + 1] = previousVertex; indices[indexCount + 2] = p;
                        cornerNormals[indexCount] = firstNormal;
                        cornerNormals[indexCount + 1] = previousNormal;
                        cornerNormals[indexCount + 2] = n;
                        indexCount += 3;
                    }
                    (previousVertex, previousNormal, previousUv) = (p, n, t);
                }
                if (corners < 3)
                    throw new InputException($"{path}:{lineNumber}", $"face has {corners} vertices (a face needs at least 3)",
                        "write 'f' with three or more vertex indices, e.g. f 1 2 3");
                faceCount++;
            }
        }
        if (faceCount == 0)
            throw new InputException($"{path}:{Math.Max(1, lineNumber)}", "no faces before the end of the file (empty mesh)",
                "the file must contain 'f' lines");

        var positionArray = positions[..positionCount];
        var mapped = MapNormals(positionCount, indices.AsSpan(0, indexCount), cornerNormals, normals.AsSpan(0, normalCount));
        var mesh = new TriangleMesh(positionArray, indices, indexCount, mapped, path,
            CornerTexCoords(cornerTexCoords.AsSpan(0, indexCount), texCoords));
        if (mesh.TriangleCount == 0)
            throw new InputException($"{path}:{Math.Max(1, lineNumber)}",
                $"at the end of the file, all {mesh.DegenerateCount} triangles are degenerate (zero area)",
                "check the vertex coordinates: every triangle has zero area");
        if (mesh.Normals is null) mesh.ComputeVertexNormals();
        return mesh;
    }

    /// <summary>The vt of every triangle corner, or null when some corner names none.</summary>
    static Vector2[]? CornerTexCoords(ReadOnlySpan<int> corners, Vector2[] texCoords)
    {
        if (texCoords.Length == 0 || corners.Length == 0) return null;
        var result = new Vector2[corners.Length];
        for (int i = 0; i < corners.Length; i++)
        {
            if (corners[i] < 0) return null;
            result[i] = texCoords[corners[i]];
        }
        return result;
    }

    /// <summary>A line with non-ASCII bytes, its Unicode white space (no-break space, em space, ...) made ' '.</summary>
    static byte[] SpacesToAscii(ReadOnlySpan<byte> line)
    {
        var chars = Encoding.UTF8.GetString(line).ToCharArray();
        for (int i = 0; i < chars.Length; i++)
            if (char.IsWhiteSpace(chars[i])) chars[i] = ' ';
        return Encoding.UTF8.GetBytes(chars);
    }

    /// <summary>Per-vertex normals from per-corner ones, or null when some vertex has none or several.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static Vector3[]? MapNormals(int vertexCount, ReadOnlySpan<int> indices, int[] cornerNormals, ReadOnlySpan<Vector3> normals)
    {
        if (normals.Length == 0) return null;
        var chosen = new int[vertexCount];
        Array.Fill(chosen, -1);
        for (int i = 0; i < indices.Length; i++)
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
    static float ReadFloat(ref Tokens tokens, string path, int line, string keyword)
    {
        var token = tokens.Next();
        if (token.Length == 0)
            throw new InputException($"{path}:{line}", $"'{keyword}' needs 3 coordinates x y z",
                "write vertices as 'v x y z' (and normals as 'vn x y z')");
        if (!TryParseFloat(token, out float value) || !float.IsFinite(value))
            throw new InputException($"{path}:{line}", $"coordinate {MessageText.Quote(token)} is not a finite number",
                "coordinates are finite decimal numbers such as 0.25 or -1e-3");
        return value;
    }

    /// <summary>10^k, exact in double for k ≤ 22.</summary>
    static readonly double[] PowersOfTen =
        [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22];

    /// <summary>
    /// A float exactly as float.TryParse (NumberStyles.Float, invariant) reads it. A plain decimal
    /// "[±]digits[.digits]" of at most 15 digits is m / 10^k with m and 10^k exact doubles, so one division
    /// rounds it correctly to double (Clinger 1990); rounding that to float is correct too unless the double
    /// lies exactly halfway between two floats. Those, and every other form, go to float.TryParse.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static bool TryParseFloat(ReadOnlySpan<byte> s, out float value)
    {
        int i = 0;
        bool negative = false;
        if (s.Length > 0 && (s[0] == '-' || s[0] == '+')) { negative = s[0] == '-'; i = 1; }
        long m = 0;
        int scale = 0, digits = 0;
        for (; i < s.Length && (uint)(s[i] - '0') <= 9; i++, digits++)
        {
            if (m >= 100_000_000_000_000) goto Slow;
            m = 10 * m + (s[i] - '0');
        }
        if (i < s.Length && s[i] == '.')
            for (i++; i < s.Length && (uint)(s[i] - '0') <= 9; i++, digits++, scale++)
            {
                if (m >= 100_000_000_000_000 || scale == 22) goto Slow;
                m = 10 * m + (s[i] - '0');
            }
        if (i != s.Length || digits == 0) goto Slow;
        double x = m / PowersOfTen[scale];
        // Halfway between two floats: the 29 bits of the double's mantissa below a float's are 1000…0.
        if ((BitConverter.DoubleToUInt64Bits(x) & 0x1FFF_FFFF) == 0x1000_0000) goto Slow;
        value = negative ? -(float)x : (float)x;
        return true;
    Slow:
        return float.TryParse(s, NumberStyles.Float, CultureInfo.InvariantCulture, out value);
    }

    /// <summary>An int exactly as int.TryParse (NumberStyles.AllowLeadingSign, invariant) reads it.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static bool TryParseInt(ReadOnlySpan<byte> s, out int value)
    {
        int i = s.Length > 0 && (s[0] == '-' || s[0] == '+') ? 1 : 0;
        if (s.Length - i is >= 1 and <= 9)
        {
            int v = 0;
            for (; i < s.Length && (uint)(s[i] - '0') <= 9; i++) v = 10 * v + (s[i] - '0');
            if (i == s.Length)
            {
                value = s[0] == '-' ? -v : v;
                return true;
            }
        }
        return int.TryParse(s, NumberStyles.AllowLeadingSign, CultureInfo.InvariantCulture, out value);
    }

    /// <summary>One face corner "v[/[vt][/vn]]" as 0-based (position, normal or -1, texture coordinate or -1).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static (int position, int normal, int texCoord) ReadCorner(ReadOnlySpan<byte> corner, int positions, int texCoords, int normals,
        string path, int line)
    {
        int slash = corner.IndexOf((byte)'/');
        int p = Resolve(slash < 0 ? corner : corner[..slash], positions, "vertex", path, line);
        if (slash < 0) return (p, -1, -1);
        var rest = corner[(slash + 1)..];
        slash = rest.IndexOf((byte)'/');
        var vt = slash < 0 ? rest : rest[..slash];
        int t = vt.Length > 0 ? Resolve(vt, texCoords, "texture coordinate", path, line) : -1;
        if (slash < 0 || slash == rest.Length - 1) return (p, -1, t);
        return (p, Resolve(rest[(slash + 1)..], normals, "normal", path, line), t);
    }

    /// <summary>A 1-based (or negative, relative) OBJ index to a 0-based one, checked against what is defined so far.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static int Resolve(ReadOnlySpan<byte> token, int count, string what, string path, int line)
    {
        if (!TryParseInt(token, out int index))
            throw new InputException($"{path}:{line}", $"{what} index {MessageText.Quote(token)} is not an integer",
                "face corners are v, v/vt, v//vn or v/vt/vn with integer indices");
        int resolved = index > 0 ? index - 1 : count + index;
        if (index == 0 || resolved < 0 || resolved >= count)
            throw new InputException($"{path}:{line}", $"{what} index {index} out of range ({count} defined so far)",
                index == 0
                    ? "OBJ indices start at 1; negative ones count back from the last"
                    : $"indices run from 1 to {count} (or -1 to -{count} counting back)");
        return resolved;
    }

    /// <summary>White-space-separated tokens of one line, as spans (no allocation).</summary>
    ref struct Tokens(ReadOnlySpan<byte> line)
    {
        ReadOnlySpan<byte> _rest = line;

        [MethodImpl(MethodImplOptions.AggressiveOptimization)]
        public ReadOnlySpan<byte> Next()
        {
            int i = 0;
            while (i < _rest.Length && IsSpace(_rest[i])) i++;
            int start = i;
            while (i < _rest.Length && !IsSpace(_rest[i])) i++;
            var token = _rest[start..i];
            _rest = _rest[i..];
            return token;
        }
    }

    /// <summary>char.IsWhiteSpace for ASCII: tab, line feed, vertical tab, form feed, carriage return and space.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static bool IsSpace(byte b) => b == ' ' || (uint)(b - '\t') <= '\r' - '\t';
}
