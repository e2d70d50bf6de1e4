using System.Numerics;
using System.Runtime.CompilerServices;

namespace SpectralRenderer.Scenes.Textures;

/// <summary>How texel indices outside the image are brought back: tiled, held at the edge, or tiled with every other copy
/// mirrored.</summary>
public enum TextureWrap
{
    Repeat,
    Clamp,
    Mirror,
}

/// <summary>
/// A texture's placement on the surface's (u, v): uv' = R(rotation)·(scale ⊙ uv) + offset (rotation counter-clockwise
/// in degrees about the uv origin), then looked up with <see cref="Wrap"/> outside [0, 1]².
/// </summary>
public readonly record struct UvTransform(Vector2 Scale, Vector2 Offset, float RotationDegrees, TextureWrap Wrap)
{
    public static UvTransform Identity { get; } = new(Vector2.One, Vector2.Zero, 0, TextureWrap.Repeat);

    /// <summary>The transformed coordinates.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public Vector2 Apply(Vector2 uv)
    {
        var s = Scale * uv;
        if (RotationDegrees != 0)
        {
            float a = RotationDegrees * (MathF.PI / 180), c = MathF.Cos(a), n = MathF.Sin(a);
            s = new Vector2(c * s.X - n * s.Y, n * s.X + c * s.Y);
        }
        return s + Offset;
    }

    /// <summary>How much the transform stretches uv lengths (the geometric mean of the scales), for the mip level.</summary>
    public float Stretch => MathF.Sqrt(MathF.Abs(Scale.X * Scale.Y));

    /// <summary>Texel index <paramref name="i"/> brought into [0, <paramref name="n"/>).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static int WrapIndex(int i, int n, TextureWrap wrap)
    {
        switch (wrap)
        {
            case TextureWrap.Clamp: return Math.Clamp(i, 0, n - 1);
            case TextureWrap.Mirror:
                {
                    int period = 2 * n, k = ((i % period) + period) % period;
                    return k < n ? k : period - 1 - k;
                }
            default: return ((i % n) + n) % n;
        }
    }
}
