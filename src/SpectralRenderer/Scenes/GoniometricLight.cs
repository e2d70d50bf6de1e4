using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A luminaire at <see cref="Position"/> whose luminous intensity I(C, γ) comes from a photometric file (IES LM-63,
/// EULUMDAT; <see cref="CandelaTable"/>). Type C angles in the luminaire's frame: γ = 0 at the nadir (−y), C = 0 towards
/// +x and C = 90° towards −z (counterclockwise seen from above, as LM-63 has it); <see cref="Orientation"/> turns that
/// frame into the world. The spectrum gives the colour: the radiant intensity is S(λ)·intensity·I(C, γ)/(K_m ∫V·S dλ),
/// so the luminous intensity is intensity × the table's candela (c_spot of eq. 2 carries I/(K_m ∫V·S), d = 1/r²).
/// </summary>
public sealed class GoniometricLight(LightEmission emission, CandelaTable table, double luminousPerUnit) : Light(emission)
{
    public Vector3 Position { get; init; }
    /// <summary>Luminaire frame → world (a rotation).</summary>
    public Matrix4x4 Orientation
    {
        get => _orientation;
        init { _orientation = value; Matrix4x4.Invert(value, out _toLocal); }
    }
    readonly Matrix4x4 _orientation = Matrix4x4.Identity, _toLocal = Matrix4x4.Identity;
    public DistanceFalloff Falloff { get; init; } = new(0, 0, 1);
    public CandelaTable Table { get; } = table;
    readonly double _perCandela = 1 / luminousPerUnit;

    public override LightExtent? Extent => new LightExtent(Position, Vector3.UnitY, -1);

    public override string Type => "goniometric";

    /// <summary>∫c_spot dω: the table's luminous flux ∫I dΩ (<see cref="CandelaTable.Flux"/>) per K_m ∫V·S dλ.</summary>
    public override double PowerPerIntensity(double sceneRadius) => Table.Flux() * _perCandela;

    public override LightDescription Describe(Radiometry radiometry) =>
        new(Type, "W.sr^-1.nm^-1 (radiant intensity) = spectrum × intensity × the file's cd / (683 lm/W · ∫V·spectrum dλ)",
            LightDescription.Of(Position), LightDescription.Of(Vector3.TransformNormal(-Vector3.UnitY, Orientation)),
                LightDescription.Of(Falloff));

    /// <summary>(C, γ) in degrees of the direction <paramref name="w"/> (world, unit) leaving the luminaire.</summary>
    public (double C, double Gamma) Angles(Vector3 w)
    {
        var v = Vector3.TransformNormal(w, _toLocal);
        double gamma = Math.Acos(Math.Clamp(-v.Y, -1, 1)) * 180 / Math.PI;
        double c = Math.Atan2(-v.Z, v.X) * 180 / Math.PI;
        return (c < 0 ? c + 360 : c, gamma);
    }

    /// <summary>The unit world direction of (C, γ) in degrees.</summary>
    public Vector3 Direction(double c, double gamma)
    {
        double cr = c * Math.PI / 180, gr = gamma * Math.PI / 180;
        var local = new Vector3((float)(Math.Sin(gr) * Math.Cos(cr)), (float)-Math.Cos(gr), (float)(-Math.Sin(gr) * Math.Sin(cr)));
        return Vector3.Normalize(Vector3.TransformNormal(local, Orientation));
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]   // hot: once per light per hit
    public override bool Illuminate(Vector3 p, out LightSample sample)
    {
        var toLight = Position - p;
        float dist = toLight.Length();
        if (dist == 0) { sample = default; return false; }
        var l = toLight / dist;
        var (c, gamma) = Angles(-l);
        float spot = (float)(Table.Evaluate(c, gamma) * _perCandela);
        if (spot == 0) { sample = default; return false; }
        sample = new LightSample(l, dist, spot, Falloff.At(dist));
        return true;
    }
}
