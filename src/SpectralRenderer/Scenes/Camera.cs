using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Scenes;

/// <summary>A pinhole camera: position, look-at, up and vertical field of view; image rows run top to bottom.</summary>
public sealed class Camera
{
    public Camera(Vector3 position, Vector3 lookAt, Vector3 up, float verticalFovDegrees, int width, int height, int samplesPerPixel)
    {
        Position = position; LookAt = lookAt; Up = up; Fov = verticalFovDegrees;
        Width = width; Height = height; SamplesPerPixel = samplesPerPixel;
        _w = Vector3.Normalize(lookAt - position);
        _u = Vector3.Normalize(Vector3.Cross(_w, up));
        _v = Vector3.Cross(_u, _w);
        _tanHalf = MathF.Tan(verticalFovDegrees * MathF.PI / 360f);
    }

    readonly Vector3 _u, _v, _w;
    readonly float _tanHalf;

    /// <summary>The film's basis as <see cref="Generate"/> uses it: right u, up v, forward w (unit vectors), and tan(fov/2).</summary>
    internal Vector3 Right => _u;
    internal Vector3 FilmUp => _v;
    internal Vector3 Forward => _w;
    internal float TanHalfFov => _tanHalf;

    public Vector3 Position { get; }
    public Vector3 LookAt { get; }
    public Vector3 Up { get; }
    public float Fov { get; }
    public int Width { get; }
    public int Height { get; }
    public int SamplesPerPixel { get; }

    public Camera With(int width, int height, int spp) => new(Position, LookAt, Up, Fov, width, height, spp);

    /// <summary>The ray through film position (px, py) in pixels, (0,0) the top-left corner.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public Ray Generate(float px, float py)
    {
        float aspect = (float)Width / Height;
        float sx = (2 * px / Width - 1) * _tanHalf * aspect;
        float sy = (1 - 2 * py / Height) * _tanHalf;
        return new Ray(Position, Vector3.Normalize(_w + sx * _u + sy * _v));
    }

    /// <summary>The pixel a world point projects to (for tests and analysis), or null behind the camera.</summary>
    public Vector2? Project(Vector3 p)
    {
        var d = p - Position;
        float z = Vector3.Dot(d, _w);
        if (z <= 0) return null;
        float aspect = (float)Width / Height;
        float sx = Vector3.Dot(d, _u) / z / (_tanHalf * aspect);
        float sy = Vector3.Dot(d, _v) / z / _tanHalf;
        return new Vector2((sx + 1) * Width / 2, (1 - sy) * Height / 2);
    }
}
