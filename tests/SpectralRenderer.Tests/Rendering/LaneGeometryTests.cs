using System.Numerics;
using System.Runtime.Intrinsics;
using SpectralRenderer.Acceleration;
using SpectralRenderer.Geometry;
using SpectralRenderer.Rendering;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// The packet path's geometry in SIMD lanes against the scalar Vector3 code it replaces, bit for bit, at every width the
/// kernels are compiled for (16, 8, 4 lanes and the scalar lane): camera rays against Camera.Generate, plane hits against
/// n·x = offset solved per ray, hit records against Normalize(Cross(…)) and the interpolated normal, and a point light's
/// direction, falloff, n·l and shadow ray against PointLight.Illuminate. (The scalar code is itself held to analytic cases
/// by the renderer's tests; PacketRenderTests renders whole pictures both ways.)
/// </summary>
public class LaneGeometryTests
{
    public static TheoryData<int> Widths => new() { 16, 8, 4, 1 };

    static void SkipUnsupported(int width)
    {
        Skip.If(width == 16 && !Vector512.IsHardwareAccelerated, "no AVX-512 here");
        Skip.If(width == 8 && !Vector256.IsHardwareAccelerated, "no 256-bit SIMD here");
        Skip.If(width == 4 && !Vector128.IsHardwareAccelerated, "no 128-bit SIMD here");
    }

    static int Bits(float f) => BitConverter.SingleToInt32Bits(f);

    static void Same(float expected, float actual, string what) =>
        Assert.True(Bits(expected) == Bits(actual),
            $"{what}: expected {expected:R} ({Bits(expected):X8}), lanes {actual:R} ({Bits(actual):X8})");

    static void Same(Vector3 expected, float x, float y, float z, string what)
    {
        Same(expected.X, x, what + ".x"); Same(expected.Y, y, what + ".y"); Same(expected.Z, z, what + ".z");
    }

    static Vector3 RandomVector(Random r, float scale) =>
        new((float)(r.NextDouble() * 2 - 1) * scale, (float)(r.NextDouble() * 2 - 1) * scale, (float)(r.NextDouble() * 2 - 1) * scale);

    [SkippableTheory]
    [MemberData(nameof(Widths))]
    public void Camera_rays_in_lanes_are_Camera_Generate_bit_for_bit(int width)
    {
        SkipUnsupported(width);
        var cam =
            new SpectralRenderer.Scenes.Camera(new Vector3(0.3f, 1.7f, 5.6f), new Vector3(0, 0.85f, 0), Vector3.UnitY, 32, 641, 479, 1);
        var r = new Random(14);
        var p = new RayPacket();
        PacketFloats fx = default, fy = default;
        for (int n = 0; n < 200; n++)
        {
            for (int lane = 0; lane < RayPacket.Size; lane++)
            {
                // Pixel corners and centres, the film's edges, and jittered positions.
                fx[lane] = n == 0 ? (lane % 4) * 0.5f * cam.Width / 1.5f : (float)(r.NextDouble() * cam.Width);
                fy[lane] = n == 0 ? (lane / 4) * 0.5f * cam.Height / 1.5f : (int)(r.NextDouble() * cam.Height) + 0.5f;
            }
            uint lanes = n % 5 == 0 ? 0x5A5Au : 0xFFFFu;
            switch (width)
            {
                case 16: LaneGeometry.CameraRays<Lanes512>(cam, ref p, ref fx, ref fy, lanes); break;
                case 8: LaneGeometry.CameraRays<Lanes256>(cam, ref p, ref fx, ref fy, lanes); break;
                case 4: LaneGeometry.CameraRays<Lanes128>(cam, ref p, ref fx, ref fy, lanes); break;
                default: LaneGeometry.CameraRays<Lanes1>(cam, ref p, ref fx, ref fy, lanes); break;
            }
            Assert.Equal(lanes, p.Active);
            for (int lane = 0; lane < RayPacket.Size; lane++)
            {
                var ray = cam.Generate(fx[lane], fy[lane]);
                Same(ray.Direction, p.DirectionX[lane], p.DirectionY[lane], p.DirectionZ[lane], $"direction at ({fx[lane]}, {fy[lane]})");
                Same(ray.Origin, p.OriginX[lane], p.OriginY[lane], p.OriginZ[lane], "origin");
                Same(ray.TMax, p.TMax[lane], "TMax");
                Assert.Equal(-1, p.Primitive[lane]);
            }
        }
    }

    [SkippableTheory]
    [MemberData(nameof(Widths))]
    public void Plane_hits_in_lanes_are_the_single_ray_plane_test(int width)
    {
        SkipUnsupported(width);
        // A floor, a tilted plane and a wall; rays from above and below, parallel to the floor (n·d = 0), with short TMax.
        (Vector3 Normal, float Offset)[] planes =
            [(Vector3.UnitY, 0), (Vector3.Normalize(new Vector3(0.3f, 1, -0.2f)), 0.7f), (Vector3.UnitX, -2)];
        var r = new Random(3);
        int hits = 0, misses = 0;
        for (int n = 0; n < 300; n++)
        {
            var p = new RayPacket();
            var rays = new Ray[RayPacket.Size];
            for (int lane = 0; lane < RayPacket.Size; lane++)
            {
                var o = RandomVector(r, 3);
                var d = Vector3.Normalize(RandomVector(r, 1));
                if (lane == 3) d = Vector3.Normalize(d with { Y = 0 });   // parallel to the floor
                float tMax = lane % 3 == 0 ? (float)r.NextDouble() * 2 : float.PositiveInfinity;
                rays[lane] = new Ray(o, d, tMax);
                p.Set(lane, rays[lane]);
            }
            PacketInts index = default;
            var blocking = p;
            uint found = width switch
            {
                16 => LaneGeometry.Planes<Lanes512>(planes, ref p, p.Active, ref index),
                8 => LaneGeometry.Planes<Lanes256>(planes, ref p, p.Active, ref index),
                4 => LaneGeometry.Planes<Lanes128>(planes, ref p, p.Active, ref index),
                _ => LaneGeometry.Planes<Lanes1>(planes, ref p, p.Active, ref index),
            };
            uint blocked = width switch
            {
                16 => LaneGeometry.PlanesBlock<Lanes512>(planes, ref blocking, blocking.Active),
                8 => LaneGeometry.PlanesBlock<Lanes256>(planes, ref blocking, blocking.Active),
                4 => LaneGeometry.PlanesBlock<Lanes128>(planes, ref blocking, blocking.Active),
                _ => LaneGeometry.PlanesBlock<Lanes1>(planes, ref blocking, blocking.Active),
            };
            for (int lane = 0; lane < RayPacket.Size; lane++)
            {
                // The closest plane in (0, TMax), planes taken in order, each shortening TMax (SceneGeometry.HitPlane).
                var ray = rays[lane];
                int expected = -1;
                for (int i = 0; i < planes.Length; i++)
                {
                    float den = Vector3.Dot(planes[i].Normal, ray.Direction);
                    float t = (planes[i].Offset - Vector3.Dot(planes[i].Normal, ray.Origin)) / den;
                    if (den != 0 && t > 0 && t < ray.TMax) { ray.TMax = t; expected = i; }
                }
                Assert.Equal(expected >= 0, (found >> lane & 1) != 0);
                Assert.Equal(expected >= 0, (blocked >> lane & 1) != 0);
                Same(ray.TMax, p.TMax[lane], $"TMax of lane {lane}");
                if (expected >= 0) { Assert.Equal(expected, index[lane]); hits++; } else misses++;
            }
        }
        Assert.True(hits > 1000 && misses > 500, $"{hits} hits, {misses} misses");
    }

    [SkippableTheory]
    [MemberData(nameof(Widths))]
    public void Hit_records_and_shading_points_in_lanes_are_the_scalar_ones(int width)
    {
        SkipUnsupported(width);
        var r = new Random(7);
        for (int n = 0; n < 300; n++)
        {
            var p = new RayPacket();
            TriangleLanes tri = default;
            HitLanes hits = default;
            var expectedG = new Vector3[RayPacket.Size];
            var expectedN = new Vector3[RayPacket.Size];
            uint mesh = 0, smooth = 0;
            for (int lane = 0; lane < RayPacket.Size; lane++)
            {
                var ray = new Ray(RandomVector(r, 4), Vector3.Normalize(RandomVector(r, 1)), (float)r.NextDouble() * 5);
                p.Set(lane, ray);
                float u = (float)r.NextDouble() * 0.6f, v = (float)r.NextDouble() * 0.4f;
                p.U[lane] = u; p.V[lane] = v;
                Vector3 a = RandomVector(r, 2), b = RandomVector(r, 2), c = RandomVector(r, 2);
                Vector3 na = Vector3.Normalize(RandomVector(r, 1)), nb = Vector3.Normalize(RandomVector(r, 1)),
                    nc = Vector3.Normalize(RandomVector(r, 1));
                if (lane == 5) { nb = -na; nc = -na; u = v = 1 / 3f; p.U[lane] = u; p.V[lane] = v; }   // |n| may vanish
                if (lane % 4 == 3)
                {   // a plane or shape lane: its normals are given
                    var g = Vector3.Normalize(RandomVector(r, 1));
                    hits.SetNormals(lane, g, g);
                    expectedG[lane] = expectedN[lane] = g;
                    continue;
                }
                mesh |= 1u << lane;
                tri.SetCorners(lane, a, b, c);
                // SceneGeometry.Record for a triangle.
                var ng = Vector3.Normalize(Vector3.Cross(b - a, c - a));
                expectedG[lane] = expectedN[lane] = ng;
                if (lane % 2 == 0)
                {
                    smooth |= 1u << lane;
                    tri.SetNormals(lane, na, nb, nc);
                    var s = (1 - u - v) * na + u * nb + v * nc;
                    if (s.LengthSquared() > 0) expectedN[lane] = Vector3.Normalize(s);
                }
            }
            ShadingLanes at = default;
            switch (width)
            {
                case 16:
                    LaneGeometry.Records<Lanes512>(ref p, mesh, smooth, in tri, ref hits);
                    LaneGeometry.Shading<Lanes512>(ref p, in hits, ref at);
                    break;
                case 8:
                    LaneGeometry.Records<Lanes256>(ref p, mesh, smooth, in tri, ref hits);
                    LaneGeometry.Shading<Lanes256>(ref p, in hits, ref at);
                    break;
                case 4:
                    LaneGeometry.Records<Lanes128>(ref p, mesh, smooth, in tri, ref hits);
                    LaneGeometry.Shading<Lanes128>(ref p, in hits, ref at);
                    break;
                default:
                    LaneGeometry.Records<Lanes1>(ref p, mesh, smooth, in tri, ref hits);
                    LaneGeometry.Shading<Lanes1>(ref p, in hits, ref at);
                    break;
            }
            for (int lane = 0; lane < RayPacket.Size; lane++)
            {
                var ray = p.Ray(lane);
                var position = ray.At(ray.TMax);
                Same(position, hits.PX[lane], hits.PY[lane], hits.PZ[lane], "position");
                Same(expectedG[lane], hits.GX[lane], hits.GY[lane], hits.GZ[lane], $"face normal of lane {lane}");
                Same(expectedN[lane], hits.NX[lane], hits.NY[lane], hits.NZ[lane], $"shading normal of lane {lane}");
                // WhittedIntegrator.Radiance's set-up: the side from the face normal, both normals to the viewer, the point above.
                var view = -ray.Direction;
                bool outside = Vector3.Dot(expectedG[lane], view) >= 0;
                var g = outside ? expectedG[lane] : -expectedG[lane];
                var nn = outside ? expectedN[lane] : -expectedN[lane];
                Same(nn, at.NX[lane], at.NY[lane], at.NZ[lane], "normal to the viewer");
                Same(g, at.GX[lane], at.GY[lane], at.GZ[lane], "face normal to the viewer");
            }
        }
    }

    [SkippableTheory]
    [MemberData(nameof(Widths))]
    public void A_point_light_in_lanes_is_Illuminate_and_the_single_ray_shadow_ray(int width)
    {
        SkipUnsupported(width);
        var light =
            new PointLight(new LightEmission("test", new float[24], new float[24], HasAmbient: false))
            {
                Position = new Vector3(2.5f, 5, 4),
                Falloff = new DistanceFalloff(1, 0.2f, 0.05f)
            };
        // The light's lane form: an isotropic point light at its position with its falloff.
        var laneForm = Assert.IsType<LanePointLight>(light.LaneForm);
        Assert.Equal(new LanePointLight(light.Position, light.Falloff), laneForm);
        var r = new Random(11);
        const float eps = 2e-5f;
        int facing = 0, away = 0;
        for (int n = 0; n < 300; n++)
        {
            ShadingLanes at = default;
            for (int lane = 0; lane < RayPacket.Size; lane++)
            {
                var pt = lane == 7 ? light.Position : RandomVector(r, 3);   // at the light: not reached (r = 0)
                var nrm = Vector3.Normalize(RandomVector(r, 1));
                at.Set(lane, pt, nrm, lane % 3 == 0 ? -nrm : nrm);   // a face normal against the shading normal too
            }
            var shadows = new RayPacket();
            PacketFloats attenuation = default, cosine = default;
            LaneVectors direction = default;
            uint lanes = n % 4 == 0 ? 0xF0F7u : 0xFFFFu, reached;
            uint lit = width switch
            {
                16 => LaneGeometry.PointLight<Lanes512>(laneForm, eps, lanes, in at, ref shadows, ref attenuation, ref cosine,
                    ref direction, out reached),
                8 => LaneGeometry.PointLight<Lanes256>(laneForm, eps, lanes, in at, ref shadows, ref attenuation, ref cosine,
                    ref direction, out reached),
                4 => LaneGeometry.PointLight<Lanes128>(laneForm, eps, lanes, in at, ref shadows, ref attenuation, ref cosine,
                    ref direction, out reached),
                _ => LaneGeometry.PointLight<Lanes1>(laneForm, eps, lanes, in at, ref shadows, ref attenuation, ref cosine,
                    ref direction, out reached),
            };
            Assert.Equal(lit, shadows.Active);
            for (int lane = 0; lane < RayPacket.Size; lane++)
            {
                bool given = (lanes >> lane & 1) != 0;
                var pt = new Vector3(at.PX[lane], at.PY[lane], at.PZ[lane]);
                bool illuminated = light.Illuminate(pt, out var ls);
                Assert.Equal(given && illuminated, (reached >> lane & 1) != 0);
                if (!given || !illuminated) { Assert.Equal(0u, lit >> lane & 1); continue; }
                float nl = Vector3.Dot(at.Normal(lane), ls.Direction);
                Same(ls.Attenuation, attenuation[lane], "attenuation");
                Same(nl, cosine[lane], "n·l");
                Assert.Equal(nl > 0, (lit >> lane & 1) != 0);
                if (nl <= 0) { away++; continue; }
                facing++;
                Same(ls.Direction, direction.X[lane], direction.Y[lane], direction.Z[lane], "l");
                // The one visibility rule (Visibility.ShadowRay), as the single ray takes it.
                var shadow = Visibility.ShadowRay(pt, at.Face(lane), ls.Direction, ls.Distance, eps);
                var s = shadows.Ray(lane);
                Same(shadow.Origin, s.Origin.X, s.Origin.Y, s.Origin.Z, "shadow origin");
                Same(shadow.Direction, s.Direction.X, s.Direction.Y, s.Direction.Z, "shadow direction");
                Same(shadow.TMax, s.TMax, "shadow TMax");
            }
        }
        Assert.True(facing > 1000 && away > 1000, $"{facing} facing, {away} away");
    }
}
