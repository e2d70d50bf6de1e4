using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering;

/// <summary>
/// The scalar geometry around a packet's traversal, done for its 16 rays in SIMD lanes (<see cref="ILanes{T}"/>):
/// camera rays (<see cref="Scenes.Camera.Generate"/>), the planes' hits (<see cref="SceneGeometry"/>'s plane test), and a
/// point light's direction, distance and falloff with n·l and the shadow ray (<see cref="PointLight.Illuminate"/>,
/// eq. 2's d_k and max(0, n·l)). Every lane does the IEEE single-precision operations of the scalar
/// <see cref="Vector3"/> code in its order — a dot product as (x·x′ + y·y′) + z·z′, a length as the square root of
/// that, a normalisation as a division by the length, no fused multiply-add — so each lane holds its ray's bits, and
/// a comparison that a NaN fails in the scalar code fails in the lane too.
/// </summary>
internal static class LaneGeometry
{
    /// <summary>
    /// The camera rays through film positions (<paramref name="filmX"/>, <paramref name="filmY"/>) (pixels) into the
    /// lanes of <paramref name="packet"/> given by <paramref name="lanes"/>, as <see cref="RayPacket.Set"/> of
    /// <see cref="Scenes.Camera.Generate"/> puts them.
    /// </summary>
    public static void CameraRays(Scenes.Camera camera, ref RayPacket packet, ref PacketFloats filmX, ref PacketFloats filmY, uint lanes)
    {
        switch (PacketLanes.Width)
        {
            case 16: CameraRays<Lanes512>(camera, ref packet, ref filmX, ref filmY, lanes); break;
            case 8: CameraRays<Lanes256>(camera, ref packet, ref filmX, ref filmY, lanes); break;
            case 4: CameraRays<Lanes128>(camera, ref packet, ref filmX, ref filmY, lanes); break;
            default: CameraRays<Lanes1>(camera, ref packet, ref filmX, ref filmY, lanes); break;
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static void CameraRays<L>(Scenes.Camera camera, ref RayPacket p, ref PacketFloats filmX, ref PacketFloats filmY,
        uint lanes) where L : struct,
        ILanes<L>
    {
        // sx = (2·px / W − 1)·tan(fov/2)·aspect, sy = (1 − 2·py / H)·tan(fov/2), d = Normalize(w + sx·u + sy·v).
        var one = L.Splat(1); var two = L.Splat(2);
        var width = L.Splat(camera.Width); var height = L.Splat(camera.Height);
        var tan = L.Splat(camera.TanHalfFov); var aspect = L.Splat((float)camera.Width / camera.Height);
        Vector3 u = camera.Right, v = camera.FilmUp, w = camera.Forward, o = camera.Position;
        var ux = L.Splat(u.X); var uy = L.Splat(u.Y); var uz = L.Splat(u.Z);
        var vx = L.Splat(v.X); var vy = L.Splat(v.Y); var vz = L.Splat(v.Z);
        var wx = L.Splat(w.X); var wy = L.Splat(w.Y); var wz = L.Splat(w.Z);
        var ox = L.Splat(o.X); var oy = L.Splat(o.Y); var oz = L.Splat(o.Z);
        var infinity = L.Splat(float.PositiveInfinity); var zero = L.Splat(0);
        for (int c = 0; c < RayPacket.Size; c += L.Count)
        {
            var sx = (two * L.Load(ref filmX[c]) / width - one) * tan * aspect;
            var sy = (one - two * L.Load(ref filmY[c]) / height) * tan;
            var dx = wx + sx * ux + sy * vx;
            var dy = wy + sx * uy + sy * vy;
            var dz = wz + sx * uz + sy * vz;
            var length = L.Sqrt(dx * dx + dy * dy + dz * dz);
            L.Store(dx / length, ref p.DirectionX[c]); L.Store(dy / length, ref p.DirectionY[c]); L.Store(dz / length, ref p.DirectionZ[c]);
            L.Store(ox, ref p.OriginX[c]); L.Store(oy, ref p.OriginY[c]); L.Store(oz, ref p.OriginZ[c]);
            L.Store(infinity, ref p.TMax[c]); L.Store(zero, ref p.U[c]); L.Store(zero, ref p.V[c]);
        }
        ((Span<int>)p.Primitive).Fill(-1);
        p.Active = lanes;
    }

    /// <summary>
    /// The planes n·x = offset against the packet's <paramref name="lanes"/> in order, as SceneGeometry tests them one ray
    /// at a time: a lane meets plane i where n·d ≠ 0 and t = (offset − n·o) / (n·d) lies in (0, TMax); its TMax becomes t
    /// and <paramref name="plane"/> the plane's index. Returns the lanes that met a plane.
    /// </summary>
    public static uint Planes(ReadOnlySpan<(Vector3 Normal, float Offset)> planes, ref RayPacket packet, uint lanes,
        ref PacketInts plane) =>
        PacketLanes.Width switch
        {
            16 => Planes<Lanes512>(planes, ref packet, lanes, ref plane),
            8 => Planes<Lanes256>(planes, ref packet, lanes, ref plane),
            4 => Planes<Lanes128>(planes, ref packet, lanes, ref plane),
            _ => Planes<Lanes1>(planes, ref packet, lanes, ref plane),
        };

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static uint Planes<L>(ReadOnlySpan<(Vector3 Normal, float Offset)> planes, ref RayPacket p, uint lanes,
        ref PacketInts plane) where L : struct,
        ILanes<L>
    {
        uint chunkMask = L.Count >= 32 ? uint.MaxValue : (1u << L.Count) - 1;
        var zero = L.Splat(0);
        uint found = 0;
        for (int c = 0; c < RayPacket.Size; c += L.Count)
        {
            uint m = (lanes >> c) & chunkMask;
            if (m == 0) continue;
            var ox = L.Load(ref p.OriginX[c]); var oy = L.Load(ref p.OriginY[c]); var oz = L.Load(ref p.OriginZ[c]);
            var dx = L.Load(ref p.DirectionX[c]); var dy = L.Load(ref p.DirectionY[c]); var dz = L.Load(ref p.DirectionZ[c]);
            var tMax = L.Load(ref p.TMax[c]);
            for (int i = 0; i < planes.Length; i++)
            {
                var (n, offset) = planes[i];
                var nx = L.Splat(n.X); var ny = L.Splat(n.Y); var nz = L.Splat(n.Z);
                var denominator = nx * dx + ny * dy + nz * dz;
                var t = (L.Splat(offset) - (nx * ox + ny * oy + nz * oz)) / denominator;
                var hit = L.AndNot(L.And(L.Greater(t, zero), L.Less(t, tMax)), L.Equal(denominator, zero));
                uint bits = L.Bits(hit) & m;
                if (bits == 0) continue;
                tMax = L.Select(L.FromBits(bits), t, tMax);
                found |= bits << c;
                for (; bits != 0; bits &= bits - 1) plane[c + BitOperations.TrailingZeroCount(bits)] = i;
            }
            L.Store(tMax, ref p.TMax[c]);
        }
        return found;
    }

    /// <summary>The lanes (of those given) whose rays meet one of the planes at t in (0, TMax): the plane test of <see cref="Planes"/>, any
    /// hit.</summary>
    public static uint PlanesBlock(ReadOnlySpan<(Vector3 Normal, float Offset)> planes, ref RayPacket packet, uint lanes) =>
        PacketLanes.Width switch
        {
            16 => PlanesBlock<Lanes512>(planes, ref packet, lanes),
            8 => PlanesBlock<Lanes256>(planes, ref packet, lanes),
            4 => PlanesBlock<Lanes128>(planes, ref packet, lanes),
            _ => PlanesBlock<Lanes1>(planes, ref packet, lanes),
        };

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static uint PlanesBlock<L>(ReadOnlySpan<(Vector3 Normal, float Offset)> planes, ref RayPacket p, uint lanes) where L : struct,
        ILanes<L>
    {
        uint chunkMask = L.Count >= 32 ? uint.MaxValue : (1u << L.Count) - 1;
        var zero = L.Splat(0);
        uint blocked = 0;
        for (int c = 0; c < RayPacket.Size; c += L.Count)
        {
            uint m = (lanes >> c) & chunkMask;
            if (m == 0) continue;
            var ox = L.Load(ref p.OriginX[c]); var oy = L.Load(ref p.OriginY[c]); var oz = L.Load(ref p.OriginZ[c]);
            var dx = L.Load(ref p.DirectionX[c]); var dy = L.Load(ref p.DirectionY[c]); var dz = L.Load(ref p.DirectionZ[c]);
            var tMax = L.Load(ref p.TMax[c]);
            for (int i = 0; i < planes.Length && m != 0; i++)
            {
                var (n, offset) = planes[i];
                var nx = L.Splat(n.X); var ny = L.Splat(n.Y); var nz = L.Splat(n.Z);
                var denominator = nx * dx + ny * dy + nz * dz;
                var t = (L.Splat(offset) - (nx * ox + ny * oy + nz * oz)) / denominator;
                uint bits = L.Bits(L.AndNot(L.And(L.Greater(t, zero), L.Less(t, tMax)), L.Equal(denominator, zero))) & m;
                blocked |= bits << c;
                m &= ~bits;
            }
        }
        return blocked;
    }

    /// <summary>
    /// The hit records of the packet's lanes, as SceneGeometry.Record makes them one ray at a time: P = o + t·d for every
    /// lane; for the <paramref name="mesh"/> lanes the face normal Normalize((p1 − p0) × (p2 − p0)), which is also the
    /// shading normal unless the lane is <paramref name="smooth"/> and n = (1 − u − v)·n0 + u·n1 + v·n2 has |n|² &gt; 0,
    /// then Normalize(n). The other lanes keep the normals already in <paramref name="hits"/> (planes, analytic shapes).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static void Records<L>(ref RayPacket p, uint mesh, uint smooth, in TriangleLanes t, ref HitLanes hits) where L : struct,
        ILanes<L>
    {
        uint chunkMask = L.Count >= 32 ? uint.MaxValue : (1u << L.Count) - 1;
        var zero = L.Splat(0); var one = L.Splat(1);
        for (int c = 0; c < RayPacket.Size; c += L.Count)
        {
            var tt = L.Load(ref p.TMax[c]);
            L.Store(L.Load(ref p.OriginX[c]) + tt * L.Load(ref p.DirectionX[c]), ref hits.PX[c]);
            L.Store(L.Load(ref p.OriginY[c]) + tt * L.Load(ref p.DirectionY[c]), ref hits.PY[c]);
            L.Store(L.Load(ref p.OriginZ[c]) + tt * L.Load(ref p.DirectionZ[c]), ref hits.PZ[c]);
            uint m = (mesh >> c) & chunkMask;
            if (m == 0) continue;
            var ax = L.Load(ref Unsafe.AsRef(in t.AX[c]));
            var ay = L.Load(ref Unsafe.AsRef(in t.AY[c]));
            var az = L.Load(ref Unsafe.AsRef(in t.AZ[c]));
            var e1x = L.Load(ref Unsafe.AsRef(in t.BX[c])) - ax;
            var e1y = L.Load(ref Unsafe.AsRef(in t.BY[c])) - ay;
            var e1z = L.Load(ref Unsafe.AsRef(in t.BZ[c])) - az;
            var e2x = L.Load(ref Unsafe.AsRef(in t.CX[c])) - ax;
            var e2y = L.Load(ref Unsafe.AsRef(in t.CY[c])) - ay;
            var e2z = L.Load(ref Unsafe.AsRef(in t.CZ[c])) - az;
            var cx = e1y * e2z - e1z * e2y;
            var cy = e1z * e2x - e1x * e2z;
            var cz = e1x * e2y - e1y * e2x;
            var length = L.Sqrt(cx * cx + cy * cy + cz * cz);
            var gx = cx / length; var gy = cy / length; var gz = cz / length;
            var isMesh = L.FromBits(m);
            L.Store(L.Select(isMesh, gx, L.Load(ref hits.GX[c])), ref hits.GX[c]);
            L.Store(L.Select(isMesh, gy, L.Load(ref hits.GY[c])), ref hits.GY[c]);
            L.Store(L.Select(isMesh, gz, L.Load(ref hits.GZ[c])), ref hits.GZ[c]);
            var nx = gx; var ny = gy; var nz = gz;
            uint s = (smooth >> c) & chunkMask;
            if (s != 0)
            {
                var u = L.Load(ref p.U[c]); var v = L.Load(ref p.V[c]);
                var w = one - u - v;
                var sx = w * L.Load(ref Unsafe.AsRef(in t.NAX[c])) + u * L.Load(ref Unsafe.AsRef(in t.NBX[c]))
                    + v * L.Load(ref Unsafe.AsRef(in t.NCX[c]));
                var sy = w * L.Load(ref Unsafe.AsRef(in t.NAY[c])) + u * L.Load(ref Unsafe.AsRef(in t.NBY[c]))
                    + v * L.Load(ref Unsafe.AsRef(in t.NCY[c]));
                var sz = w * L.Load(ref Unsafe.AsRef(in t.NAZ[c])) + u * L.Load(ref Unsafe.AsRef(in t.NBZ[c]))
                    + v * L.Load(ref Unsafe.AsRef(in t.NCZ[c]));
                var squared = sx * sx + sy * sy + sz * sz;
                var interpolated = L.And(L.FromBits(s), L.Greater(squared, zero));
                var sl = L.Sqrt(squared);
                nx = L.Select(interpolated, sx / sl, nx);
                ny = L.Select(interpolated, sy / sl, ny);
                nz = L.Select(interpolated, sz / sl, nz);
            }
            L.Store(L.Select(isMesh, nx, L.Load(ref hits.NX[c])), ref hits.NX[c]);
            L.Store(L.Select(isMesh, ny, L.Load(ref hits.NY[c])), ref hits.NY[c]);
            L.Store(L.Select(isMesh, nz, L.Load(ref hits.NZ[c])), ref hits.NZ[c]);
        }
    }

    /// <summary>
    /// The shading points of the given lanes, as the single-ray Radiance sets them up: v = −d; the face normal decides the
    /// side (outside when n_g·v ≥ 0) and both normals are turned to the viewer's side.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static void Shading<L>(ref RayPacket p, in HitLanes h, ref ShadingLanes at) where L : struct, ILanes<L>
    {
        var zero = L.Splat(0);
        for (int c = 0; c < RayPacket.Size; c += L.Count)
        {
            var vx = L.Negate(L.Load(ref p.DirectionX[c]));
            var vy = L.Negate(L.Load(ref p.DirectionY[c]));
            var vz = L.Negate(L.Load(ref p.DirectionZ[c]));
            var gx = L.Load(ref Unsafe.AsRef(in h.GX[c]));
            var gy = L.Load(ref Unsafe.AsRef(in h.GY[c]));
            var gz = L.Load(ref Unsafe.AsRef(in h.GZ[c]));
            var outside = L.LessOrEqual(zero, gx * vx + gy * vy + gz * vz);
            gx = L.Select(outside, gx, L.Negate(gx)); gy = L.Select(outside, gy, L.Negate(gy)); gz = L.Select(outside, gz, L.Negate(gz));
            var nx = L.Load(ref Unsafe.AsRef(in h.NX[c]));
            var ny = L.Load(ref Unsafe.AsRef(in h.NY[c]));
            var nz = L.Load(ref Unsafe.AsRef(in h.NZ[c]));
            L.Store(L.Select(outside, nx, L.Negate(nx)), ref at.NX[c]);
            L.Store(L.Select(outside, ny, L.Negate(ny)), ref at.NY[c]);
            L.Store(L.Select(outside, nz, L.Negate(nz)), ref at.NZ[c]);
            var px = L.Load(ref Unsafe.AsRef(in h.PX[c]));
            var py = L.Load(ref Unsafe.AsRef(in h.PY[c]));
            var pz = L.Load(ref Unsafe.AsRef(in h.PZ[c]));
            L.Store(px, ref at.PX[c]); L.Store(py, ref at.PY[c]); L.Store(pz, ref at.PZ[c]);
            L.Store(gx, ref at.GX[c]); L.Store(gy, ref at.GY[c]); L.Store(gz, ref at.GZ[c]);
        }
    }

    /// <summary>
    /// An isotropic point light (<see cref="Light.LaneForm"/>, as <see cref="PointLight.Illuminate"/>) seen
    /// from the points P of the given lanes (<paramref name="at"/>),
    /// with shading normals n: the lanes it reaches (distance r ≠ 0) in
    /// <paramref name="reached"/>; their attenuation 1 / (c0 + c1·r + c2·r²) and n·l. The lanes that face it (not n·l ≤ 0)
    /// get l in <paramref name="direction"/> and their shadow ray in <paramref name="shadows"/>, whose active lanes they
    /// become: <see cref="Visibility.ShadowRay"/>'s, operation for operation (the origin P ± ε·n_g on l's side, aimed from
    /// there at P + r·l, TMax its length − 2ε). Returns those lanes.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    internal static uint PointLight<L>(in LanePointLight light, float epsilon, uint lanes, in ShadingLanes at,
        ref RayPacket shadows, ref PacketFloats attenuation, ref PacketFloats cosine, ref LaneVectors direction, out uint reached)
        where L : struct, ILanes<L>
    {
        uint chunkMask = L.Count >= 32 ? uint.MaxValue : (1u << L.Count) - 1;
        var zero = L.Splat(0); var one = L.Splat(1);
        var lx = L.Splat(light.Position.X); var ly = L.Splat(light.Position.Y); var lz = L.Splat(light.Position.Z);
        var f = light.Falloff;
        var c0 = L.Splat(f.C0); var c1 = L.Splat(f.C1); var c2 = L.Splat(f.C2);
        var eps = L.Splat(epsilon); var minusEps = L.Splat(-epsilon); var twoEps = L.Splat(2 * epsilon);
        uint facing = 0;
        reached = 0;
        for (int c = 0; c < RayPacket.Size; c += L.Count)
        {
            uint m = (lanes >> c) & chunkMask;
            if (m == 0) continue;
            var tx = lx - L.Load(ref Unsafe.AsRef(in at.PX[c]));
            var ty = ly - L.Load(ref Unsafe.AsRef(in at.PY[c]));
            var tz = lz - L.Load(ref Unsafe.AsRef(in at.PZ[c]));
            var r = L.Sqrt(tx * tx + ty * ty + tz * tz);
            m &= ~L.Bits(L.Equal(r, zero));
            reached |= m << c;
            if (m == 0) continue;
            var dx = tx / r; var dy = ty / r; var dz = tz / r;
            var nl = L.Load(ref Unsafe.AsRef(in at.NX[c])) * dx + L.Load(ref Unsafe.AsRef(in at.NY[c])) * dy
                + L.Load(ref Unsafe.AsRef(in at.NZ[c])) * dz;
            L.Store(one / (c0 + c1 * r + c2 * r * r), ref attenuation[c]);
            L.Store(nl, ref cosine[c]);
            uint lit = m & ~L.Bits(L.LessOrEqual(nl, zero));
            if (lit == 0) continue;
            facing |= lit << c;
            L.Store(dx, ref direction.X[c]); L.Store(dy, ref direction.Y[c]); L.Store(dz, ref direction.Z[c]);
            // Visibility.ShadowRay: origin O = P + (±ε)·n_g on l's side, towards (P + r·l) − O, its length less 2ε.
            var px = L.Load(ref Unsafe.AsRef(in at.PX[c]));
            var py = L.Load(ref Unsafe.AsRef(in at.PY[c]));
            var pz = L.Load(ref Unsafe.AsRef(in at.PZ[c]));
            var gx = L.Load(ref Unsafe.AsRef(in at.GX[c]));
            var gy = L.Load(ref Unsafe.AsRef(in at.GY[c]));
            var gz = L.Load(ref Unsafe.AsRef(in at.GZ[c]));
            var sideEps = L.Select(L.LessOrEqual(zero, gx * dx + gy * dy + gz * dz), eps, minusEps);
            var ox = px + sideEps * gx; var oy = py + sideEps * gy; var oz = pz + sideEps * gz;
            var wx = px + r * dx - ox; var wy = py + r * dy - oy; var wz = pz + r * dz - oz;
            var length = L.Sqrt(wx * wx + wy * wy + wz * wz);
            L.Store(ox, ref shadows.OriginX[c]); L.Store(oy, ref shadows.OriginY[c]); L.Store(oz, ref shadows.OriginZ[c]);
            L.Store(wx / length, ref shadows.DirectionX[c]); L.Store(wy / length, ref shadows.DirectionY[c]);
            L.Store(wz / length, ref shadows.DirectionZ[c]);
            L.Store(length - twoEps, ref shadows.TMax[c]);
        }
        shadows.Active = facing;
        return facing;
    }
}

/// <summary>A packet's closest hits in lanes: point P, unit face normal G and unit shading normal N (outward, not yet facing the ray),
/// object.</summary>
internal struct HitLanes
{
    public PacketFloats PX, PY, PZ, GX, GY, GZ, NX, NY, NZ;
    public PacketInts Object;

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void SetNormals(int lane, Vector3 geometric, Vector3 shading)
    {
        GX[lane] = geometric.X; GY[lane] = geometric.Y; GZ[lane] = geometric.Z;
        NX[lane] = shading.X; NY[lane] = shading.Y; NZ[lane] = shading.Z;
    }
}

/// <summary>Per lane, the corners of the triangle hit and (smooth meshes) its vertex normals.</summary>
internal struct TriangleLanes
{
    public PacketFloats AX, AY, AZ, BX, BY, BZ, CX, CY, CZ;
    public PacketFloats NAX, NAY, NAZ, NBX, NBY, NBZ, NCX, NCY, NCZ;

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void SetCorners(int lane, Vector3 a, Vector3 b, Vector3 c)
    {
        AX[lane] = a.X;
        AY[lane] = a.Y;
        AZ[lane] = a.Z;
        BX[lane] = b.X;
        BY[lane] = b.Y;
        BZ[lane] = b.Z;
        CX[lane] = c.X;
        CY[lane] = c.Y;
        CZ[lane] = c.Z;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void SetNormals(int lane, Vector3 a, Vector3 b, Vector3 c)
    {
        NAX[lane] = a.X;
        NAY[lane] = a.Y;
        NAZ[lane] = a.Z;
        NBX[lane] = b.X;
        NBY[lane] = b.Y;
        NBZ[lane] = b.Z;
        NCX[lane] = c.X;
        NCY[lane] = c.Y;
        NCZ[lane] = c.Z;
    }
}

/// <summary>A packet's shading points in lanes: hit position P, shading normal N and face normal G, both on the viewer's
/// side.</summary>
internal struct ShadingLanes
{
    public PacketFloats PX, PY, PZ, NX, NY, NZ, GX, GY, GZ;

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Set(int lane, Vector3 p, Vector3 n, Vector3 g)
    {
        PX[lane] = p.X; PY[lane] = p.Y; PZ[lane] = p.Z;
        NX[lane] = n.X; NY[lane] = n.Y; NZ[lane] = n.Z;
        GX[lane] = g.X; GY[lane] = g.Y; GZ[lane] = g.Z;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public readonly Vector3 Normal(int lane) => new(NX[lane], NY[lane], NZ[lane]);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public readonly Vector3 Face(int lane) => new(GX[lane], GY[lane], GZ[lane]);
}

/// <summary>A unit vector per lane (a light's direction l).</summary>
internal struct LaneVectors
{
    public PacketFloats X, Y, Z;
}
