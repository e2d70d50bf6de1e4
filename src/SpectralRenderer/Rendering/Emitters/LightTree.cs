using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// Where an emitter with extent is and where it can shine (Conty Estevez &amp; Kulla 2018, "Importance Sampling of Many
/// Lights with Adaptive Tree Splitting", §4.1; pbrt-v4's <c>LightBounds</c>): its world <paramref name="Box"/>, the cone of
/// its surface normals (or a spot's axis) about the unit <paramref name="Axis"/> with half-angle θ_o
/// (<paramref name="CosSpread"/>; −1 for every direction), how far beyond a normal it still emits, θ_e
/// (<paramref name="CosEmission"/>: 0 for a Lambertian surface, θ_e = π/2; 1 for a point or spot light, which shines only
/// inside its cone) and whether it emits from both sides of its normals.
/// </summary>
internal readonly record struct EmitterBounds(Bounds3 Box, Vector3 Axis, float CosSpread, float CosEmission, bool TwoSided);

/// <summary>
/// A bounding volume hierarchy over emitters with extent (Conty Estevez &amp; Kulla 2018; pbrt-v4's <c>BVHLightSampler</c>),
/// each node with its spatial bounds, its directional bounds (normal cone θ_o, emission spread θ_e) and its power Φ:
/// next-event estimation walks it from the root, at each node taking a child with probability proportional to the child's
/// importance seen from the shading point p with normal n,
/// <code>
///   I = Φ·cos θ′/d²·cos θ′_i,   θ′ = max(0, θ_w − θ_o − θ_b),   θ′_i = max(0, θ_i − θ_b)
/// </code>
/// (d the distance from the node's centre, θ_w the angle between the cone's axis and the direction to p, θ_b the half-angle
/// of the node's bounding sphere seen from p, θ_i the angle between n and that direction; I = 0 when θ′ &gt; θ_e, where no
/// point of the node can shine towards p; the receiver's factor dropped when n = 0, in a medium). The probability of an
/// emitter is the product of the choices on its path (<see cref="Pmf"/>, walked down again by its recorded trail of left and
/// right), so a BSDF-sampled ray that hits it gets the density next-event estimation has for it, and the product over the
/// members sums to 1 wherever some member has an importance. The build splits at the median centroid along the widest
/// axis of the centroids (ties by emitter index): deterministic, and the choice depends only on p, n and u, never on a
/// thread. No allocation when choosing.
/// </summary>
internal sealed class LightTree
{
    struct Node
    {
        public Vector3 Centre, Axis;
        public float Radius, CosSpread, CosEmission, Phi;
        public bool TwoSided;
        public int Second;    // the second child's index (the first is the next node); −1 at a leaf
        public int Emitter;   // the leaf's emitter
    }

    readonly Node[] _nodes;
    readonly ulong[] _trail;   // by emitter index: the choices down to its leaf, bit l set for the second child at depth l
    readonly int[] _depth;     // by emitter index: its leaf's depth, −1 for an emitter not in the tree

    /// <summary>The tree over <paramref name="members"/>: each emitter's index in its set, its bounds and its power Φ (&gt; 0
    /// somewhere, else nothing is ever chosen).</summary>
    public LightTree(IReadOnlyList<(int Emitter, EmitterBounds Bounds, double Phi)> members)
    {
        if (members.Count == 0) throw new ArgumentException("a light tree needs at least one emitter");
        int size = members.Max(m => m.Emitter) + 1;
        _trail = new ulong[size];
        _depth = new int[size];
        Array.Fill(_depth, -1);
        var nodes = new List<Node>(2 * members.Count);
        var order = Enumerable.Range(0, members.Count).ToArray();
        Build(members, order, 0, order.Length, nodes, 0, 0, out _, out _);
        _nodes = [.. nodes];
    }

    /// <summary>The number of emitters in the tree.</summary>
    public int Count { get; private set; }

    /// <summary>Does the tree hold emitter <paramref name="emitter"/>?</summary>
    public bool Contains(int emitter) => emitter >= 0 && emitter < _depth.Length && _depth[emitter] >= 0;

    /// <summary>Builds the node of members order[from..to) at the end of <paramref name="nodes"/>; its box and normal cone out.</summary>
    void Build(IReadOnlyList<(int Emitter, EmitterBounds Bounds, double Phi)> members, int[] order, int from, int to,
        List<Node> nodes, ulong trail, int depth, out Bounds3 box, out (Vector3 Axis, float Cos) cone)
    {
        int index = nodes.Count;
        nodes.Add(default);
        if (to - from == 1)
        {
            var (emitter, b, phi) = members[order[from]];
            box = b.Box;
            cone = (b.Axis, b.CosSpread);
            nodes[index] = new Node
            {
                Centre = box.Centre,
                Radius = 0.5f * box.Extent.Length(),
                Axis = b.Axis,
                CosSpread = b.CosSpread,
                CosEmission = b.CosEmission,
                Phi = (float)phi,
                TwoSided = b.TwoSided,
                Second = -1,
                Emitter = emitter,
            };
            _trail[emitter] = trail;
            _depth[emitter] = depth;
            Count++;
            return;
        }
        var centroids = Bounds3.Empty;
        for (int i = from; i < to; i++) centroids.Include(members[order[i]].Bounds.Box.Centre);
        var extent = centroids.Extent;
        int axis = extent.X >= extent.Y && extent.X >= extent.Z ? 0 : extent.Y >= extent.Z ? 1 : 2;
        Array.Sort(order, from, to - from, Comparer<int>.Create((a, c) =>
        {
            int byCentre = members[a].Bounds.Box.Centre[axis].CompareTo(members[c].Bounds.Box.Centre[axis]);
            return byCentre != 0 ? byCentre : members[a].Emitter.CompareTo(members[c].Emitter);
        }));
        int mid = (from + to) / 2;
        if (depth >= 63) throw new InvalidOperationException("light tree deeper than its trail holds");
        Build(members, order, from, mid, nodes, trail, depth + 1, out var boxA, out var coneA);
        int second = nodes.Count;
        Build(members, order, mid, to, nodes, trail | (1UL << depth), depth + 1, out var boxB, out var coneB);
        box = boxA;
        box.Include(boxB);
        cone = Union(coneA, coneB);
        Node a = nodes[index + 1], c = nodes[second];
        nodes[index] = new Node
        {
            Centre = box.Centre,
            Radius = 0.5f * box.Extent.Length(),
            Axis = cone.Axis,
            CosSpread = cone.Cos,
            CosEmission = MathF.Min(a.CosEmission, c.CosEmission),
            Phi = a.Phi + c.Phi,
            TwoSided = a.TwoSided || c.TwoSided,
            Second = second,
            Emitter = -1,
        };
    }

    /// <summary>
    /// The smallest cone about a direction between the two axes that holds both cones (the half-angle
    /// (θ_a + θ_d + θ_b)/2, θ_d between the axes; the whole sphere when that reaches π or the axes are opposed).
    /// </summary>
    static (Vector3 Axis, float Cos) Union((Vector3 Axis, float Cos) a, (Vector3 Axis, float Cos) b)
    {
        if (a.Cos <= -1 || b.Cos <= -1) return (Vector3.UnitY, -1);
        double ta = Math.Acos(Math.Clamp(a.Cos, -1, 1)), tb = Math.Acos(Math.Clamp(b.Cos, -1, 1));
        double td = Math.Acos(Math.Clamp(Vector3.Dot(a.Axis, b.Axis), -1, 1));
        if (Math.Min(td + tb, Math.PI) <= ta) return a;
        if (Math.Min(td + ta, Math.PI) <= tb) return b;
        double to = (ta + td + tb) / 2;
        if (to >= Math.PI) return (Vector3.UnitY, -1);
        var perpendicular = b.Axis - Vector3.Dot(a.Axis, b.Axis) * a.Axis;
        if (perpendicular.LengthSquared() < 1e-12f) return (Vector3.UnitY, -1);
        perpendicular = Vector3.Normalize(perpendicular);
        double turn = to - ta;   // the axis turned from a towards b
        var axis = Vector3.Normalize((float)Math.Cos(turn) * a.Axis + (float)Math.Sin(turn) * perpendicular);
        // a little wider than exact, so rounding never leaves a member's normal outside
        return (axis, (float)Math.Cos(Math.Min(Math.PI, to + 1e-5)));
    }

    /// <summary>cos max(0, A − B) from the cosines and sines of A and B.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float CosMinus(float cosA, float sinA, float cosB, float sinB) => cosA >= cosB ? 1 : cosA * cosB + sinA * sinB;

    /// <summary>sin max(0, A − B) from the cosines and sines of A and B.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float SinMinus(float cosA, float sinA, float cosB, float sinB) => cosA >= cosB ? 0 : sinA * cosB - cosA * sinB;

    /// <summary>The importance I of node <paramref name="node"/> seen from <paramref name="p"/> (normal <paramref name="n"/>,
    /// or 0): the class summary's formula.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    static float Importance(in Node node, Vector3 p, Vector3 n)
    {
        var d = p - node.Centre;
        float d2 = d.LengthSquared(), r2 = node.Radius * node.Radius;
        if (!(d2 > 0)) return node.Phi / MathF.Max(r2, 1e-30f);
        var wi = d / MathF.Sqrt(d2);
        float cosB = -1, sinB = 0;   // inside the bounding sphere: it fills every direction
        if (d2 > r2)
        {
            float sin2 = r2 / d2;
            cosB = MathF.Sqrt(1 - sin2);
            sinB = MathF.Sqrt(sin2);
        }
        float cosW = Vector3.Dot(node.Axis, wi);
        if (node.TwoSided) cosW = MathF.Abs(cosW);
        float sinW = MathF.Sqrt(MathF.Max(0, 1 - cosW * cosW)), sinO = MathF.Sqrt(MathF.Max(0, 1 - node.CosSpread * node.CosSpread));
        float cosX = CosMinus(cosW, sinW, node.CosSpread, sinO), sinX = SinMinus(cosW, sinW, node.CosSpread, sinO);
        float cosP = CosMinus(cosX, sinX, cosB, sinB);
        if (cosP < node.CosEmission) return 0;
        float importance = node.Phi * MathF.Max(cosP, 0) / MathF.Max(d2, r2);
        if (n != Vector3.Zero)
        {
            float cosI = MathF.Abs(Vector3.Dot(wi, n)), sinI = MathF.Sqrt(MathF.Max(0, 1 - cosI * cosI));
            importance *= CosMinus(cosI, sinI, cosB, sinB);
        }
        return importance;
    }

    /// <summary>
    /// The emitter the walk from the root takes for <paramref name="u"/> ∈ [0, 1) seen from <paramref name="p"/> (normal
    /// <paramref name="n"/>), and its probability; −1 (probability 0) when no member can shine towards p.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public int Choose(Vector3 p, Vector3 n, float u, out float pmf)
    {
        var nodes = _nodes;
        int i = 0;
        pmf = 1;
        while (nodes[i].Second >= 0)
        {
            float a = Importance(in nodes[i + 1], p, n), b = Importance(in nodes[nodes[i].Second], p, n);
            if (!(a + b > 0)) { pmf = 0; return -1; }
            float first = a / (a + b);
            if (u < first)
            {
                u = MathF.Min(u / first, OneBelow);
                pmf *= first;
                i++;
            }
            else
            {
                u = MathF.Min((u - first) / (1 - first), OneBelow);
                pmf *= 1 - first;
                i = nodes[i].Second;
            }
        }
        return nodes[i].Emitter;
    }

    /// <summary>The probability that <see cref="Choose"/> from <paramref name="p"/> (normal <paramref name="n"/>) takes
    /// <paramref name="emitter"/>, a member: the same choices, down its trail.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public float Pmf(Vector3 p, Vector3 n, int emitter)
    {
        ulong trail = _trail[emitter];
        int depth = _depth[emitter];
        var nodes = _nodes;
        int i = 0;
        float pmf = 1;
        for (int level = 0; level < depth; level++)
        {
            float a = Importance(in nodes[i + 1], p, n), b = Importance(in nodes[nodes[i].Second], p, n);
            if (!(a + b > 0)) return 0;
            float first = a / (a + b);
            if ((trail >> level & 1) == 0)
            {
                pmf *= first;
                i++;
            }
            else
            {
                pmf *= 1 - first;
                i = nodes[i].Second;
            }
        }
        return pmf;
    }

    /// <summary>The largest float below 1.</summary>
    const float OneBelow = 0.99999994f;
}
