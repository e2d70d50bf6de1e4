using System.Buffers.Binary;
using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Geometry;

/// <summary>
/// Reads a triangle mesh from a PLY file (ascii, binary_little_endian or binary_big_endian): the vertex
/// element's x y z (and nx ny nz when all three are present, texture coordinates u v — or s t, texture_u texture_v — when
/// both are), of any scalar type; polygons from the 'face'
/// element's vertex_indices (or vertex_index) list, fan-triangulated; triangle strips from a 'tristrips'
/// element's vertex_indices list, where −1 restarts a strip and every second triangle is flipped to keep the
/// winding. Other properties and elements are skipped. The whole file is read into memory and parsed as bytes:
/// binary elements in bulk, by offsets into the bytes; ascii ones value by value with a <see cref="PlyCursor"/>.
/// </summary>
public static class PlyReader
{
    public static TriangleMesh Read(string path)
    {
        return Parse(InputFile.ReadAllBytes(path, "mesh file"), path);
    }

    public static TriangleMesh Parse(ReadOnlySpan<byte> data, string path)
    {
        var header = PlyHeader.Parse(data, path);
        var elements = header.Elements;
        PlyElement? vertexElement = null;
        foreach (var e in elements)
            if (e.Name == "vertex") { vertexElement = e; break; }
        if (vertexElement is null)
            throw new InputException($"{path}: header", "the header declares no 'vertex' element",
                "a mesh needs 'element vertex N' with x, y, z properties");
        for (int a = 0; a < 3; a++)
        {
            int i = vertexElement.IndexOf("xyz"[a..(a + 1)]);
            if (i < 0 || vertexElement.Properties[i].IsList)
                throw new InputException($"{path}:{vertexElement.HeaderLine}", $"element 'vertex' has no scalar property '{"xyz"[a]}'",
                    "declare 'property float x' (and y, z) in the vertex element");
        }
        bool hasFaces = false;
        foreach (var e in elements) hasFaces |= e.Name is "face" or "tristrips";
        if (!hasFaces)
            throw new InputException($"{path}: header",
                "the header declares no 'face' or 'tristrips' element (a point cloud is not a mesh)",
                "a mesh needs 'element face N' with a vertex_indices list");

        // Header checks come before any data is read.
        var listIndex = new int[elements.Count]; // the vertex-index list of each face/tristrips element
        for (int i = 0; i < elements.Count; i++)
            listIndex[i] = elements[i].Name is "face" or "tristrips" ? IndexList(elements[i], path) : -1;

        int vertexCount = vertexElement.Count;
        bool binary = header.Format != PlyFormat.Ascii;
        bool le = header.Format == PlyFormat.BinaryLittleEndian;
        var mesh = new MeshData();
        long faces = 0;
        foreach (var e in elements) if (e.Name == "face") faces += e.Count;
        mesh.Indices = new int[Math.Min(3 * faces, data.Length)]; // exact for triangles; strips reserve per list
        int pos = header.DataStart;
        for (int i = 0; i < elements.Count; i++)
        {
            var element = elements[i];
            // Each instance takes at least one byte: refuse absurd counts before allocating for them.
            if (element.Count > data.Length - pos)
                throw PlyCursor.Error(path, element.Name, 0, pos,
                    $"{element.Count} instances cannot fit in the {data.Length - pos} bytes left (truncated file?)",
                        "the header's element counts do not match the data: export the mesh again");
            bool strips = element.Name == "tristrips";
            int end = !binary ? -1
                : ReferenceEquals(element, vertexElement) ? ReadVertices(data, pos, element, le, path, mesh)
                : ReadLists(data, pos, element, listIndex[i], strips, le, vertexCount, path, mesh);
            if (end < 0)
            {
                // Ascii, or a binary element the bulk path leaves to the cursor (which says where the data ends).
                var cursor = new PlyCursor(data, pos, header.Format, path) { Element = element.Name };
                if (ReferenceEquals(element, vertexElement)) ReadVertices(ref cursor, element, mesh);
                else if (listIndex[i] >= 0) ReadLists(ref cursor, element, listIndex[i], strips, vertexCount, mesh);
                else SkipElement(ref cursor, element);
                end = cursor.Position;
            }
            pos = end;
        }

        Vector2[]? cornerUvs = null;
        if (mesh.TexCoords is { } uvs)
        {
            cornerUvs = new Vector2[mesh.IndexCount];
            for (int i = 0; i < cornerUvs.Length; i++) cornerUvs[i] = uvs[mesh.Indices[i]];
        }
        var result = new TriangleMesh(mesh.Positions, mesh.Indices, mesh.IndexCount, mesh.Normals, path, cornerUvs);
        if (result.TriangleCount == 0)
            throw new InputException($"{path}: end of data",
                result.DegenerateCount == 0 ? "no faces (empty mesh)" : $"all {result.DegenerateCount} triangles are degenerate",
                "check the vertex coordinates and faces: nothing of area is left");
        if (result.Normals is null) result.ComputeVertexNormals();
        return result;
    }

    /// <summary>What the body gives: vertices, triangles (three indices each, growing) and a list buffer.</summary>
    sealed class MeshData
    {
        public Vector3[] Positions = [];
        public Vector3[]? Normals;
        public Vector2[]? TexCoords;
        public int[] Indices = [];
        public int IndexCount;
        int[] _list = new int[64];

        /// <summary>Room for <paramref name="triangles"/> more triangles at the end of <see cref="Indices"/>.</summary>
        public Span<int> Reserve(int triangles)
        {
            long need = IndexCount + 3L * triangles;
            if (need > Indices.Length) Array.Resize(ref Indices, (int)Math.Min(Math.Max(need, 2L * Indices.Length), Array.MaxLength));
            return Indices.AsSpan(IndexCount);
        }

        /// <summary>A scratch buffer for one list's vertex indices.</summary>
        public Span<int> List(int count)
        {
            if (count > _list.Length) _list = new int[Math.Max(count, 2 * _list.Length)];
            return _list.AsSpan(0, count);
        }

        /// <summary>A polygon, fan-triangulated: (first, previous, this) for each corner after the second.</summary>
        public void AddFan(ReadOnlySpan<int> corners)
        {
            var into = Reserve(corners.Length - 2);
            int w = 0;
            for (int c = 2; c < corners.Length; c++)
            {
                into[w] = corners[0]; into[w + 1] = corners[c - 1]; into[w + 2] = corners[c];
                w += 3;
            }
            IndexCount += w;
        }

        /// <summary>Triangle strips separated by −1: triangle i of a strip is (v[i], v[i+1], v[i+2]) for even i
        /// and (v[i+1], v[i], v[i+2]) for odd i, so all keep the first one's winding.</summary>
        [MethodImpl(MethodImplOptions.AggressiveOptimization)]
        public void AddStrips(ReadOnlySpan<int> items)
        {
            var into = Reserve(Math.Max(items.Length - 2, 0));
            int w = 0, a = -1, b = -1, inStrip = 0; // the two previous vertices of the current strip
            foreach (int v in items)
            {
                if (v < 0) { inStrip = 0; continue; }
                if (inStrip >= 2)
                {
                    if ((inStrip & 1) == 0) { into[w] = a; into[w + 1] = b; }
                    else { into[w] = b; into[w + 1] = a; }
                    into[w + 2] = v;
                    w += 3;
                }
                a = b; b = v; inStrip++;
            }
            IndexCount += w;
        }
    }

    /// <summary>Which property of a face/tristrips element holds the vertex indices.</summary>
    static int IndexList(PlyElement e, string path)
    {
        int i = e.IndexOf("vertex_indices");
        if (i < 0) i = e.IndexOf("vertex_index");
        if (i < 0 || !e.Properties[i].IsList)
            throw new InputException($"{path}:{e.HeaderLine}", $"element '{e.Name}' has no list property 'vertex_indices'",
                "faces are 'property list uchar int vertex_indices'");
        if (!PlyHeader.IsInteger(e.Properties[i].Type))
            throw new InputException($"{path}:{e.HeaderLine}", $"element '{e.Name}': vertex indices must have an integer type",
                "declare vertex_indices as a list of int or uint");
        return i;
    }

    /// <summary>Role of each vertex property: 0..2 position x y z, 3..5 normal x y z, 6..7 texture u v, -1 skipped.</summary>
    static int[] VertexRoles(PlyElement e)
    {
        var roles = new int[e.Properties.Count];
        for (int i = 0; i < roles.Length; i++)
        {
            roles[i] = e.Properties[i].IsList ? -1 : Array.IndexOf(RoleNames, e.Properties[i].Name);
            if (roles[i] < 0 && !e.Properties[i].IsList)
                roles[i] = e.Properties[i].Name switch { "s" or "texture_u" => 6, "t" or "texture_v" => 7, _ => -1 };
        }
        // A second name for a texture coordinate (u and s both given) keeps the first.
        for (int i = 0; i < roles.Length; i++)
            if (roles[i] >= 6 && Array.IndexOf(roles, roles[i]) < i) roles[i] = -1;
        return roles;
    }

    static readonly string[] RoleNames = ["x", "y", "z", "nx", "ny", "nz", "u", "v"];
    const int Roles = 8;

    static bool HasNormals(int[] roles) => Array.IndexOf(roles, 3) >= 0 && Array.IndexOf(roles, 4) >= 0 && Array.IndexOf(roles, 5) >= 0;
    static bool HasTexCoords(int[] roles) => Array.IndexOf(roles, 6) >= 0 && Array.IndexOf(roles, 7) >= 0;

    /// <summary>
    /// The binary vertex element in bulk: each instance is a fixed-size record, each role a value at a fixed
    /// offset in it. Returns where the element ends, or -1 when the cursor must read it (a list property, a
    /// repeated name, or data that ends inside the element).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static int ReadVertices(ReadOnlySpan<byte> data, int start, PlyElement e, bool le, string path, MeshData mesh)
    {
        int stride = e.FixedSize;
        if (stride < 0 || (long)e.Count * stride > data.Length - start) return -1;
        var roles = VertexRoles(e);
        // The properties with a role, in file order: offset in the record, type, role.
        int used = 0, offset = 0, seen = 0;
        Span<int> offsets = stackalloc int[Roles], targets = stackalloc int[Roles];
        Span<PlyType> types = stackalloc PlyType[Roles];
        for (int i = 0; i < roles.Length; i++)
        {
            if (roles[i] >= 0)
            {
                if ((seen & (1 << roles[i])) != 0) return -1;
                seen |= 1 << roles[i];
                offsets[used] = offset; types[used] = e.Properties[i].Type; targets[used] = roles[i]; used++;
            }
            offset += PlyHeader.SizeOf(e.Properties[i].Type);
        }
        offsets = offsets[..used]; types = types[..used]; targets = targets[..used];

        var positions = new Vector3[e.Count];
        var normals = HasNormals(roles) ? new Vector3[e.Count] : null;
        var uvs = HasTexCoords(roles) ? new Vector2[e.Count] : null;
        bool justXyz = le && used == 3 && stride == 12 && offsets[1] == 4 && offsets[2] == 8 && targets[0] == 0 && targets[1] == 1
            && types[0] == PlyType.Float32 && types[1] == PlyType.Float32 && types[2] == PlyType.Float32;
        if (justXyz && BitConverter.IsLittleEndian)
        {
            // Records of three little-endian floats are the positions as they lie in memory.
            MemoryMarshal.Cast<byte, Vector3>(data.Slice(start, 12 * e.Count)).CopyTo(positions);
            for (int k = 0; k < positions.Length; k++)
                if (!float.IsFinite(positions[k].X + positions[k].Y + positions[k].Z))
                    CheckFinite(data, start + 12 * k, e, k, offsets, types, targets, le, path);
        }
        else ReadRecords(data, start, stride, e, offsets, types, targets, le, path, positions, normals, uvs);
        mesh.Positions = positions;
        mesh.Normals = normals;
        mesh.TexCoords = uvs;
        return start + e.Count * stride;
    }

    /// <summary>Vertex records of any layout: each role's value decoded at its offset (a method of its own, so
    /// the common x y z layout does not compile it).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void ReadRecords(ReadOnlySpan<byte> data, int start, int stride, PlyElement e, ReadOnlySpan<int> offsets,
        ReadOnlySpan<PlyType> types, ReadOnlySpan<int> targets, bool le, string path, Vector3[] positions, Vector3[]? normals,
            Vector2[]? uvs)
    {
        Span<float> v = stackalloc float[Roles];
        for (int k = 0; k < positions.Length; k++)
        {
            var record = data.Slice(start + k * stride, stride);
            for (int j = 0; j < offsets.Length; j++)
            {
                float value = (float)PlyCursor.DecodeReal(types[j], record[offsets[j]..], le);
                if (!float.IsFinite(value)) CheckFinite(data, start + k * stride, e, k, offsets, types, targets, le, path);
                v[targets[j]] = value;
            }
            positions[k] = new Vector3(v[0], v[1], v[2]);
            if (normals is not null) normals[k] = SafeNormalize(new Vector3(v[3], v[4], v[5]));
            if (uvs is not null) uvs[k] = new Vector2(v[6], v[7]);
        }
    }

    /// <summary>Throws for the first value of vertex record <paramref name="k"/> that is not finite.</summary>
    static void CheckFinite(ReadOnlySpan<byte> data, int record, PlyElement e, int k, ReadOnlySpan<int> offsets,
        ReadOnlySpan<PlyType> types, ReadOnlySpan<int> targets, bool le, string path)
    {
        for (int j = 0; j < offsets.Length; j++)
        {
            float value = (float)PlyCursor.DecodeReal(types[j], data[(record + offsets[j])..], le);
            if (!float.IsFinite(value))
            {
                string name = RoleNames[targets[j]];
                throw PlyCursor.Error(path, e.Name, k, record + offsets[j], $"property '{name}' is {value}, not a finite number",
                    "vertex coordinates must be finite numbers: export the mesh again");
            }
        }
    }

    /// <summary>
    /// A binary element in bulk: with <paramref name="listIndex"/> ≥ 0 a face or tristrips element whose
    /// vertex indices are triangulated, otherwise one to skip. Returns where the element ends, or -1 when the
    /// data ends inside it (the cursor then reads it again and says where).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static int ReadLists(ReadOnlySpan<byte> data, int start, PlyElement e, int listIndex, bool strips, bool le, int vertexCount,
        string path, MeshData mesh)
    {
        int stride = e.FixedSize;
        if (stride >= 0) return (long)e.Count * stride > data.Length - start ? -1 : start + e.Count * stride; // no list: skip
        var properties = e.Properties;
        int pos = start;
        for (int k = 0; k < e.Count; k++)
        {
            for (int i = 0; i < properties.Count; i++)
            {
                var p = properties[i];
                int size = PlyHeader.SizeOf(p.Type);
                if (!p.IsList)
                {
                    if (data.Length - pos < size) return -1;
                    pos += size;
                    continue;
                }
                int countSize = PlyHeader.SizeOf(p.CountType);
                if (data.Length - pos < countSize) return -1;
                long n = PlyCursor.DecodeInteger(p.CountType, data[pos..], le);
                if (n < 0)
                    throw PlyCursor.Error(path, e.Name, k, pos, $"list '{p.Name}' has negative length {n}",
                        "the file is corrupt at this place: export the mesh again");
                if (i == listIndex && !strips && n < 3)
                    throw PlyCursor.Error(path, e.Name, k, pos, $"face has {n} vertices (a face needs at least 3)",
                        "every face needs three or more vertex indices");
                pos += countSize;
                if (n * size > data.Length - pos) return -1;
                int bytes = (int)n * size;
                if (i == listIndex)
                {
                    var items = mesh.List((int)n);
                    Decode(data.Slice(pos, bytes), p.Type, le, items);
                    for (int j = 0; j < items.Length; j++)
                        if ((uint)items[j] >= (uint)vertexCount && !(strips && items[j] == -1))
                            throw PlyCursor.Error(path, e.Name, k, pos + j * size,
                                $"vertex index {PlyCursor.DecodeInteger(p.Type, data[(pos + j * size)..], le)} out of "
                                    + $"range ({vertexCount} vertices)",
                                    "vertex indices count from 0 to the vertex count − 1");
                    if (strips) mesh.AddStrips(items);
                    else mesh.AddFan(items);
                }
                pos += bytes;
            }
        }
        return pos;
    }

    /// <summary>
    /// Binary integers to ints: −1 (or the largest uint32, its two's-complement twin) stays −1, the strip
    /// restart; a uint32 above int.MaxValue becomes negative, an index out of range either way.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void Decode(ReadOnlySpan<byte> bytes, PlyType type, bool le, Span<int> into)
    {
        switch (type)
        {
            case PlyType.Int32 or PlyType.UInt32:
                var ints = MemoryMarshal.Cast<byte, int>(bytes);
                if (le == BitConverter.IsLittleEndian) ints.CopyTo(into);
                else BinaryPrimitives.ReverseEndianness(ints, into);
                break;
            case PlyType.Int8:
                for (int i = 0; i < into.Length; i++) into[i] = (sbyte)bytes[i];
                break;
            case PlyType.UInt8:
                for (int i = 0; i < into.Length; i++) into[i] = bytes[i];
                break;
            default: // 16-bit
                for (int i = 0; i < into.Length; i++) into[i] = (int)PlyCursor.DecodeInteger(type, bytes[(2 * i)..], le);
                break;
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void ReadVertices(ref PlyCursor cursor, PlyElement e, MeshData mesh)
    {
        var roles = VertexRoles(e);
        var positions = new Vector3[e.Count];
        var normals = HasNormals(roles) ? new Vector3[e.Count] : null;
        var uvs = HasTexCoords(roles) ? new Vector2[e.Count] : null;
        Span<float> v = stackalloc float[Roles];
        for (int k = 0; k < e.Count; k++)
        {
            cursor.Instance = k;
            for (int i = 0; i < roles.Length; i++)
            {
                var p = e.Properties[i];
                if (roles[i] < 0) { cursor.Skip(p); continue; }
                float value = (float)cursor.ReadReal(p.Type);
                if (!float.IsFinite(value))
                    throw cursor.Error($"property '{p.Name}' is {value}, not a finite number",
                        "vertex coordinates must be finite numbers: export the mesh again");
                v[roles[i]] = value;
            }
            positions[k] = new Vector3(v[0], v[1], v[2]);
            if (normals is not null) normals[k] = SafeNormalize(new Vector3(v[3], v[4], v[5]));
            if (uvs is not null) uvs[k] = new Vector2(v[6], v[7]);
        }
        mesh.Positions = positions;
        mesh.Normals = normals;
        mesh.TexCoords = uvs;
    }

    static Vector3 SafeNormalize(Vector3 n)
    {
        float len = n.Length();
        return len > 0 ? n / len : Vector3.UnitZ;
    }

    /// <summary>A face or tristrips element, value by value.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    static void ReadLists(ref PlyCursor cursor, PlyElement e, int listIndex, bool strips, int vertexCount, MeshData mesh)
    {
        var list = e.Properties[listIndex];
        for (int k = 0; k < e.Count; k++)
        {
            cursor.Instance = k;
            for (int i = 0; i < e.Properties.Count; i++)
            {
                if (i != listIndex) { cursor.Skip(e.Properties[i]); continue; }
                long n = cursor.ReadCount(list);
                if (!strips && n < 3)
                    throw cursor.Error($"face has {n} vertices (a face needs at least 3)", "every face needs three or more vertex indices");
                // Each item takes at least one byte: refuse absurd counts before allocating for them.
                var items = mesh.List((int)Math.Min(n, cursor.Remaining + 1));
                for (int c = 0; c < n; c++)
                {
                    long raw = cursor.ReadInteger(list.Type);
                    if (strips && (raw == -1 || (list.Type == PlyType.UInt32 && raw == uint.MaxValue))) { items[c] = -1; continue; }
                    if (raw < 0 || raw >= vertexCount)
                        throw cursor.Error($"vertex index {raw} out of range ({vertexCount} vertices)",
                            "vertex indices count from 0 to the vertex count − 1");
                    items[c] = (int)raw;
                }
                if (strips) mesh.AddStrips(items);
                else mesh.AddFan(items);
            }
        }
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
