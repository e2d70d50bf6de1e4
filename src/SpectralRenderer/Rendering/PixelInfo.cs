namespace SpectralRenderer.Rendering;

/// <summary>
/// What the camera ray of a pixel saw, for the analysis images: the lights that reach the surface point
/// (n·l &gt; 0, inside the cone, shadow ray unblocked; bit k = light k) and the luminance Y of the
/// diffuse and specular terms of eq. 2 there.
/// </summary>
public struct PixelInfo
{
    public uint LitMask;
    public float DiffuseY;
    public float SpecularY;

    /// <summary>mask-highlight.png's value (§3.4): 255 where the specular term's luminance is positive and exceeds
    /// <paramref name="fraction"/> (the scene's output.highlight_fraction) times the diffuse term's, else 0.</summary>
    public static byte Highlight(float specularY, float diffuseY, float fraction) =>
        specularY > 0 && specularY > fraction * diffuseY ? (byte)255 : (byte)0;
}
