using System.Runtime.CompilerServices;

namespace SpectralRenderer.Rendering;

/// <summary>
/// Per pixel, which lights reach the surface its centre ray sees (<see cref="PixelInfo.LitMask"/>: bit k = light k,
/// k &lt; 32), in as few bytes per pixel as the scene's lights need: one for up to 8 lights (1 MB at 1024², where a
/// uint per pixel would take 4), four for 25–32.
/// </summary>
public sealed class LitMasks
{
    /// <summary>The most lights a mask tells apart (the analysis images write mask-lit-K.png for K below it).</summary>
    public const int MaxLights = 32;

    readonly byte[] _bytes;

    /// <summary>Masks for <paramref name="pixels"/> pixels of a scene with <paramref name="lights"/> lights, each to be set once (not
    /// zeroed first).</summary>
    public LitMasks(int pixels, int lights)
    {
        Count = pixels;
        BytesPerPixel = Math.Max(1, (Math.Clamp(lights, 0, MaxLights) + 7) / 8);
        _bytes = GC.AllocateUninitializedArray<byte>(pixels * BytesPerPixel);
    }

    /// <summary>Masks holding <paramref name="masks"/> (one uint per pixel, as the light transfer keeps them).</summary>
    public static LitMasks From(uint[] masks, int lights)
    {
        var m = new LitMasks(masks.Length, lights);
        for (int i = 0; i < masks.Length; i++) m[i] = masks[i];
        return m;
    }

    public int Count { get; }
    public int BytesPerPixel { get; }

    /// <summary>Pixel <paramref name="pixel"/>'s mask; setting drops the bits of lights the scene does not have.</summary>
    public uint this[int pixel]
    {
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        get
        {
            int at = pixel * BytesPerPixel;
            uint mask = 0;
            for (int b = 0; b < BytesPerPixel; b++) mask |= (uint)_bytes[at + b] << (8 * b);
            return mask;
        }
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        set
        {
            int at = pixel * BytesPerPixel;
            for (int b = 0; b < BytesPerPixel; b++) _bytes[at + b] = (byte)(value >> (8 * b));
        }
    }

    /// <summary>Does light <paramref name="light"/> reach the surface pixel <paramref name="pixel"/> sees?</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public bool IsLit(int pixel, int light) =>
        (uint)light < 8u * (uint)BytesPerPixel && (_bytes[pixel * BytesPerPixel + (light >> 3)] & (1 << (light & 7))) != 0;

    /// <summary>The masks, one uint per pixel.</summary>
    public uint[] ToArray()
    {
        var a = new uint[Count];
        for (int i = 0; i < Count; i++) a[i] = this[i];
        return a;
    }
}
