using System.Runtime.InteropServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Rendering;

/// <summary>
/// The triangle BVHs of the last few scenes a process rendered, for commands that render scene after scene
/// (`spectral experiments`: one statue under four lights; `spectral sweep`: one mesh under many lights and
/// materials): a scene whose meshes hold the same triangles — the same vertex positions, bit for bit, and the same
/// indices, in the same order — gets the BVH already built instead of building it again. The build is
/// deterministic, so a reused tree is the one a new build would give, and every image is the same.
/// Thread-safe; holds at most <see cref="Capacity"/> triangle sets, the least recently used dropped first.
/// </summary>
public sealed class GeometryCache
{
    public const int Capacity = 3;

    readonly List<(TriangleMesh[] Meshes, TriangleSet Set)> _entries = [];
    readonly Lock _lock = new();

    /// <summary>How many scenes were given a BVH built for an earlier scene.</summary>
    public int Reused { get; private set; }

    /// <summary>The BVH and triangles of <paramref name="meshes"/>: one built for the same triangles, else built now and kept.</summary>
    internal TriangleSet Triangles(TriangleMesh[] meshes)
    {
        lock (_lock)
        {
            for (int i = 0; i < _entries.Count; i++)
                if (SameTriangles(_entries[i].Meshes, meshes))
                {
                    var hit = _entries[i];
                    _entries.RemoveAt(i);
                    _entries.Add(hit);
                    Reused++;
                    return hit.Set;
                }
        }
        var set = TriangleSet.Build(meshes);
        lock (_lock)
        {
            if (_entries.Count == Capacity) _entries.RemoveAt(0);
            _entries.Add((meshes, set));
        }
        return set;
    }

    /// <summary>Whether the two lists hold the same triangles: positions compared as bits, indices as integers.</summary>
    static bool SameTriangles(TriangleMesh[] a, TriangleMesh[] b)
    {
        if (a.Length != b.Length) return false;
        for (int m = 0; m < a.Length; m++)
        {
            if (ReferenceEquals(a[m], b[m])) continue;
            if (!MemoryMarshal.AsBytes(a[m].Positions.AsSpan()).SequenceEqual(MemoryMarshal.AsBytes(b[m].Positions.AsSpan()))
                || !a[m].Indices.AsSpan().SequenceEqual(b[m].Indices)) return false;
        }
        return true;
    }
}
