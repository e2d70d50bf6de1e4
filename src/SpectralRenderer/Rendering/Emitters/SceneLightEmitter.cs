using System.Numerics;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Rendering.Emitters;

/// <summary>
/// A scene light (<see cref="Light"/>: point, spot, directional, goniometric, or a kind added by a registration) in the
/// emitter set: its sample is <see cref="Light.Sample"/>'s (eq. 2's direction, distance and d_k·c_spot,k on I_k). Scene
/// lights are delta lights: no ray hits them, so their pdf and emitted radiance are 0 (a light with extent is an emitting
/// object, <see cref="ShapeEmitter"/>).
/// </summary>
internal sealed class SceneLightEmitter(Light light, int index, float[] intensity) : Emitter(intensity)
{
    public override bool IsDelta => true;
    public override int SceneLight => index;

    public override bool Sample(Vector3 p, Vector3 front, Vector2 u, out EmitterSample sample)
    {
        if (!light.Sample(p, u, out var inc)) { sample = default; return false; }
        sample = new EmitterSample(inc.Direction, inc.Distance, inc.Factor, inc.Pdf, inc.IsDelta);
        return true;
    }

    /// <summary>Φ/I: the light's <see cref="Light.PowerPerIntensity"/> (4π for a point light, πR² for a directional one).</summary>
    public override double PowerPerRadiance(double sceneRadius) => light.PowerPerIntensity(sceneRadius);

    /// <summary>A light at a point: the point, its cone θ_o and no spread beyond it (θ_e = 0); null at infinity.</summary>
    public override EmitterBounds? Bounds => light.Extent is { } x
        ? new EmitterBounds(new Bounds3(x.Position, x.Position), x.Axis, x.CosHalfAngle, 1, false) : null;

    public override float Pdf(Vector3 p, Vector3 front, Vector3 wi, Vector3 x, Vector3 nx) => 0;
    public override float Emitted(Vector3 n, Vector3 wo) => 0;
    public override string Describe() => $"{light.Type} light '{light.Name}'";
}
