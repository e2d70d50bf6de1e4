using System.Numerics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Scenes.Loading;

/// <summary>
/// A shape type of the scene file beyond the built-in sphere, plane, quad and box: the keys it takes besides "type",
/// "name", "material" and "transform", its canonical shape (<see cref="CanonicalShape"/>, object space) and where the
/// object's keys place it (the object-to-scene matrix, before the object's "transform").
/// </summary>
public sealed record ShapeType(string[] Keys, CanonicalShape Shape, Func<SceneLoader.ShapeSource, Matrix4x4> Place);

/// <summary>
/// The registered shape types a scene file can name ("type"): the one registration point for a new kind of analytic
/// shape, which then works as a plain object and, with an emissive material, as an area light of the path tracer.
/// The built-in sphere, plane, quad and box are placed by SceneLoader.Objects.cs (their fast paths in Acceleration/).
/// </summary>
public static class ShapeTypes
{
    static readonly Lock Gate = new();
    static Dictionary<string, ShapeType> s_byName = new(StringComparer.Ordinal)
    {
        // A disk: "center", "radius", and its +z side facing "normal", "up" the texture's v (as a quad's).
        ["disk"] = new(["center", "radius", "normal", "up"], new Disk(), s =>
            Matrix4x4.CreateScale(s.Size("radius"), s.Size("radius"), 1) * s.Frame("normal", "up") * s.Translation("center")),
        // An open tube (Mitsuba's cylinder): from "p0" to "p1" with "radius"; u runs around it, v from p0 to p1.
        ["cylinder"] = new(["p0", "p1", "radius"], new Cylinder(), Tube),
    };

    public static IReadOnlyDictionary<string, ShapeType> ByName => Volatile.Read(ref s_byName);

    /// <summary>Adds a shape type under a new (lower-case) name; loads that start afterwards can use it.</summary>
    public static void Register(string name, ShapeType type)
    {
        if (name is "sphere" or "plane" or "quad" or "box" or "mesh" or "colorchecker")
            throw new ArgumentException($"'{name}' is a built-in object type", nameof(name));
        Registry.Add(ref s_byName, Gate, name, type);
    }

    static Matrix4x4 Tube(SceneLoader.ShapeSource s)
    {
        var p0 = s.Point("p0", Vector3.Zero);
        var p1 = s.Point("p1", Vector3.UnitZ);
        float length = (p1 - p0).Length(), r = s.Size("radius");
        if (!(length >= SceneLoader.MinSize))
            throw s.Error("p1", $"the cylinder's ends p0 and p1 are {length} apart", $"give p1 at least {SceneLoader.MinSize} from p0");
        var axis = (p1 - p0) / length;
        // The seam (u = 0) faces the scene's x (or z for an x-axis tube): any frame with z along the axis.
        var up = MathF.Abs(axis.X) < 0.9f ? Vector3.UnitX : Vector3.UnitZ;
        return Matrix4x4.CreateScale(r, r, length) * s.Frame(axis, Vector3.Cross(axis, up)) * Matrix4x4.CreateTranslation(p0);
    }
}
