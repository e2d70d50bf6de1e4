using System.Numerics;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// An emitting object in the emitter set: a point on its surface drawn by <see cref="AreaEmitter"/> (by solid angle on a
/// round sphere, by area on any other shape kind, a registered one included), L_e where the surface faces the point.
/// </summary>
internal sealed class ShapeEmitter(AreaEmitter area, string name) : Emitter(area.Radiance, area.Texture)
{
    public override bool IsDelta => false;

    /// <summary>The surface point as <see cref="AreaEmitter.Sample(Vector3, Vector2, out Vector3, out Vector3, out float, out int)"/>
    /// draws it, seen along ω_i = (x − p)/|x − p|; nothing when x is at p or its surface faces away.</summary>
    public override bool Sample(Vector3 p, Vector3 front, Vector2 u, out EmitterSample sample)
    {
        sample = default;
        if (!area.Sample(p, u, out var x, out var nx, out float pdf, out int face)) return false;
        var d = x - p;
        float distance = d.Length();
        if (!(distance > 0)) return false;
        var wi = d / distance;
        if (!area.Emits(nx, -wi)) return false;
        sample = new EmitterSample(wi, distance, 1, pdf, false, x, nx, face);
        return true;
    }

    /// <summary>Φ/L = π·A per emitting side (a Lambertian surface of area A; two-sided: 2πA).</summary>
    public override double PowerPerRadiance(double sceneRadius) => Math.PI * area.Area * (area.TwoSided ? 2 : 1);

    public override EmitterBounds? Bounds { get; } = area.Bounds();
    public override float Pdf(Vector3 p, Vector3 front, Vector3 wi, Vector3 x, Vector3 nx) => area.Pdf(p, x, nx);
    public override float Emitted(Vector3 n, Vector3 wo) => area.Emits(n, wo) ? 1 : 0;
    public override Vector2 TexCoord(int face, Vector3 x, out float uvPerLength) => area.TexCoord(face, x, out uvPerLength);
    public override string Describe() => $"emitting object '{name}'";
}
