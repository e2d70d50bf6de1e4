using System.Numerics;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// The sky seen through window portals (<see cref="Portal"/>, <c>"portal": true</c> on a quad in an opening; Bitterli et al.
/// 2015, "Portal-Masked Environment Map Sampling"; pbrt-v4's <c>PortalImageInfiniteLight</c>): from a point on the inner
/// side of a portal (n·(p − c) &gt; 0, n into the room) a sky direction is drawn from the one-sample mixture
/// <code>
///   p(ω) = ½·p_sky(ω) + ½·p_portals(ω),   p_portals(ω) = (1/J)·Σ_j [p + tω meets portal j at x_j]·t_j²/(A_j·|n_j·ω|)
/// </code>
/// — the sky's own strategy (<see cref="SkyEmitter"/>, <see cref="OvercastSkyEmitter"/>, <see cref="EnvironmentEmitter"/>),
/// and a point uniform on the area of one of the J portals, chosen uniformly —, so skylight that enters by the window is
/// drawn where it comes from and the sky's own draw still covers every other opening (the mixture is the balance heuristic of
/// the two, Veach 1997, §9.2.2, and <see cref="Pdf"/> its density for a BSDF ray's MIS weight). From the outer side the
/// sky's own strategy alone. What the sky sends along a direction is the sky's (<see cref="Emitted"/>); rays pass portals.
/// </summary>
internal sealed class PortalSkyEmitter(Emitter sky, IReadOnlyList<Portal> portals) : Emitter(sky.Radiance, sky.Texture)
{
    readonly Portal[] _portals = [.. portals];

    /// <summary>The sky's own strategy's share of the mixture.</summary>
    const float SkyShare = 0.5f;

    /// <summary>The sky whose directions the portals are drawn for.</summary>
    public Emitter Sky => sky;

    public override bool IsDelta => false;
    public override double PowerPerRadiance(double sceneRadius) => sky.PowerPerRadiance(sceneRadius);
    public override float Emitted(Vector3 n, Vector3 wo) => sky.Emitted(n, wo);
    public override string Describe() => $"{sky.Describe()} through {_portals.Length} portal(s)";

    /// <summary>Is <paramref name="p"/> on the inner side of some portal (where the mixture draws)?</summary>
    bool Inside(Vector3 p)
    {
        foreach (var w in _portals) if (Vector3.Dot(w.Normal, p - w.Corner) > 0) return true;
        return false;
    }

    public override bool Sample(Vector3 p, Vector3 front, Vector2 u, out EmitterSample sample)
    {
        if (!Inside(p)) return sky.Sample(p, front, u, out sample);
        sample = default;
        Vector3 wi;
        if (u.X < SkyShare)
        {
            if (!sky.Sample(p, front, new Vector2(MathF.Min(u.X / SkyShare, 0.99999994f), u.Y), out var own) || !(own.Pdf > 0))
                return false;
            wi = own.Direction;
        }
        else
        {   // a portal by the rest of u.X, a point uniform on it by what is left of it and u.Y
            float v = (u.X - SkyShare) / (1 - SkyShare) * _portals.Length;
            int j = Math.Min((int)v, _portals.Length - 1);
            float a = Math.Clamp(v - j, 0, 0.99999994f);
            var w = _portals[j];
            var d = w.Corner + a * w.Edge1 + u.Y * w.Edge2 - p;
            float length = d.Length();
            if (!(length > 0)) return false;
            wi = d / length;
        }
        float factor = sky.Emitted(default, -wi);
        float pdf = Pdf(p, front, wi, default, default);
        if (!(factor > 0) || !(pdf > 0) || !float.IsFinite(pdf)) return false;
        sample = new EmitterSample(wi, float.PositiveInfinity, factor, pdf, false);
        return true;
    }

    public override float Pdf(Vector3 p, Vector3 front, Vector3 wi, Vector3 x, Vector3 nx)
    {
        float own = sky.Pdf(p, front, wi, x, nx);
        if (!Inside(p)) return own;
        float through = 0;
        foreach (var w in _portals)
        {
            // p + t·wi meets the portal's plane at t = n·(c − p)/(n·wi); inside when its (a, b) ∈ [0, 1]².
            float cos = Vector3.Dot(w.Normal, wi);
            if (cos == 0) continue;
            float t = Vector3.Dot(w.Normal, w.Corner - p) / cos;
            if (!(t > 0)) continue;
            var r = p + t * wi - w.Corner;
            float e11 = w.Edge1.LengthSquared(), e22 = w.Edge2.LengthSquared(), e12 = Vector3.Dot(w.Edge1, w.Edge2);
            float r1 = Vector3.Dot(r, w.Edge1), r2 = Vector3.Dot(r, w.Edge2), det = e11 * e22 - e12 * e12;
            float a = (r1 * e22 - r2 * e12) / det, b = (r2 * e11 - r1 * e12) / det;
            if (a is < 0 or > 1 || b is < 0 or > 1) continue;
            through += t * t / (w.Area * MathF.Abs(cos));
        }
        return SkyShare * own + (1 - SkyShare) * through / _portals.Length;
    }
}
