using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Geometry;

/// <summary>
/// Reads a triangle mesh from a PLY file (ascii, binary_little_endian or binary_big_endian): the vertex
/// element's x y z (and nx ny nz when all three are present), of any scalar type; polygons from the 'face'
/// element's vertex_indices (or vertex_index) list, fan-triangulated; triangle strips from a 'tristrips'
/// element's vertex_indices list, where −1 restarts a strip and every second triangle is flipped to keep the
/// winding. Other properties and elements are skipped. The whole file is read into memory and parsed as bytes.
/// </summary>
public static class PlyReader
{
    public static TriangleMesh Read(string path)
    {
        return Parse(InputFile.ReadAllBytes(path), path);
    }

    public static TriangleMesh Parse(ReadOnlySpan<byte> data, string path)
    {
        var header = PlyHeader.Parse(data, path);
        var vertexElement = header.Elements.Find(e => e.Name == "vertex")
            ?? throw new InputException(path, "the header declares no 'vertex' element");
        var xyz = new[] { vertexElement.IndexOf("x"), vertexElement.IndexOf("y"), vertexElement.IndexOf("z") };
        for (int a = 0; a < 3; a++)
            if (xyz[a] < 0 || vertexElement.Properties[xyz[a]].IsList)
                throw new InputException($"{path}:{vertexElement.HeaderLine}", $"element 'vertex' has no scalar property '{"xyz"[a]}'");
        if (!header.Elements.Any(e => e.Name is "face" or "tristrips"))
            throw new InputException(path, "the header declares no 'face' or 'tristrips' element (a point cloud is not a mesh)");

        // Header checks come before any data is read.
        var indexLists = header.Elements.Where(e => e.Name is "face" or "tristrips").ToDictionary(e => e, e => IndexList(e, path));

        int vertexCount = vertexElement.Count;
        var cursor = new PlyCursor(data, header.DataStart, header.Format, path);
        Vector3[] positions = [];
        Vector3[]? normals = null;
        var indices = new List<int>();
        foreach (var element in header.Elements)
        {
            cursor.Element = element.Name;
            cursor.Instance = 0;
            // Each instance takes at least one byte: refuse absurd counts before allocating for them.
            if (element.Count > data.Length - cursor.Position)
                throw cursor.Error($"{element.Count} instances cannot fit in the {data.Length - cursor.Position} bytes left (truncated file?)");
            if (element == vertexElement) (positions, normals) = ReadVertices(ref cursor, element);
            else if (element.Name == "face") ReadFaces(ref cursor, element, indexLists[element], vertexCount, indices);
            else if (element.Name == "tristrips") ReadStrips(ref cursor, element, indexLists[element], vertexCount, indices);
            else SkipElement(ref cursor, element);
        }

        var mesh = new TriangleMesh(positions, indices.ToArray(), normals, path);
        if (mesh.TriangleCount == 0)
            throw new InputException(path, mesh.DegenerateCount == 0 ? "no faces (empty mesh)" : $"all {mesh.DegenerateCount} triangles are degenerate");
        if (mesh.Normals is null) mesh.ComputeVertexNormals();
        return mesh;
    }

    /// <summary>Which property of a face/tristrips element holds the vertex indices.</summary>
    static int IndexList(PlyElement e, string path)
    {
        int i = e.IndexOf("vertex_indices");
        if (i < 0) i = e.IndexOf("vertex_index");
        if (i < 0 || !e.Properties[i].IsList)
            throw new InputException($"{path}:{e.HeaderLine}", $"element '{e.Name}' has no list property 'vertex_indices'");
        if (!PlyHeader.IsInteger(e.Properties[i].Type))
            throw new InputException($"{path}:{e.HeaderLine}", $"element '{e.Name}': vertex indices must have an integer type");
        return i;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static (Vector3[] positions, Vector3[]? normals) ReadVertices(ref PlyCursor cursor, PlyElement e)
    {
        // Role of each property: 0..2 position x y z, 3..5 normal x y z, -1 skipped.
        var roles = new int[e.Properties.Count];
        string[] names = ["x", "y", "z", "nx", "ny", "nz"];
        for (int i = 0; i < roles.Length; i++) roles[i] = e.Properties[i].IsList ? -1 : Array.IndexOf(names, e.Properties[i].Name);
        bool hasNormals = roles.Contains(3) && roles.Contains(4) && roles.Contains(5);

        var positions = new Vector3[e.Count];
        var normals = hasNormals ? new Vector3[e.Count] : null;
        Span<float> v = stackalloc float[6];
        for (int k = 0; k < e.Count; k++)
        {
            cursor.Instance = k;
            for (int i = 0; i < roles.Length; i++)
            {
                var p = e.Properties[i];
                if (roles[i] < 0) { cursor.Skip(p); continue; }
                float value = (float)cursor.ReadReal(p.Type);
                if (!float.IsFinite(value)) throw cursor.Error($"property '{p.Name}' is {value}, not a finite number");
                v[roles[i]] = value;
            }
            positions[k] = new Vector3(v[0], v[1], v[2]);
            if (normals is not null) normals[k] = SafeNormalize(new Vector3(v[3], v[4], v[5]));
        }
        return (positions, normals);
    }

    static Vector3 SafeNormalize(Vector3 n)
    {
        float len = n.Length();
        return len > 0 ? n / len : Vector3.UnitZ;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void ReadFaces(ref PlyCursor cursor, PlyElement e, int listIndex, int vertexCount, List<int> indices)
    {
        var list = e.Properties[listIndex];
        for (int k = 0; k < e.Count; k++)
        {
            cursor.Instance = k;
            for (int i = 0; i < e.Properties.Count; i++)
            {
                if (i != listIndex) { cursor.Skip(e.Properties[i]); continue; }
                long n = cursor.ReadCount(list);
                if (n < 3) throw cursor.Error($"face has {n} vertices (a face needs at least 3)");
                int first = ReadIndex(ref cursor, list.Type, vertexCount);
                int previous = ReadIndex(ref cursor, list.Type, vertexCount);
                for (long c = 2; c < n; c++)
                {
                    int current = ReadIndex(ref cursor, list.Type, vertexCount);
                    indices.Add(first); indices.Add(previous); indices.Add(current); // fan
                    previous = current;
                }
            }
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void ReadStrips(ref PlyCursor cursor, PlyElement e, int listIndex, int vertexCount, List<int> indices)
    {
        var list = e.Properties[listIndex];
        for (int k = 0; k < e.Count; k++)
        {
            cursor.Instance = k;
            for (int i = 0; i < e.Properties.Count; i++)
            {
                if (i != listIndex) { cursor.Skip(e.Properties[i]); continue; }
                long n = cursor.ReadCount(list);
                int a = -1, b = -1, inStrip = 0; // the two previous vertices of the current strip
                for (long c = 0; c < n; c++)
                {
                    long raw = cursor.ReadInteger(list.Type);
                    if (raw == -1 || (list.Type == PlyType.UInt32 && raw == uint.MaxValue)) { inStrip = 0; continue; }
                    int v = CheckIndex(ref cursor, raw, vertexCount);
                    if (inStrip >= 2)
                    {
                        // Triangle i of a strip is (v[i], v[i+1], v[i+2]) for even i and (v[i+1], v[i], v[i+2]) for odd i.
                        if ((inStrip & 1) == 0) { indices.Add(a); indices.Add(b); }
                        else { indices.Add(b); indices.Add(a); }
                        indices.Add(v);
                    }
                    a = b; b = v; inStrip++;
                }
            }
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static int ReadIndex(ref PlyCursor cursor, PlyType type, int vertexCount) =>
        CheckIndex(ref cursor, cursor.ReadInteger(type), vertexCount);

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static int CheckIndex(ref PlyCursor cursor, long index, int vertexCount)
    {
        if (index < 0 || index >= vertexCount)
            throw cursor.Error($"vertex index {index} out of range ({vertexCount} vertices)");
        return (int)index;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void SkipElement(ref PlyCursor cursor, PlyElement e)
    {
        for (int k = 0; k < e.Count; k++)
        {
            cursor.Instance = k;
            foreach (var p in e.Properties) cursor.Skip(p);
        }
    }
}
