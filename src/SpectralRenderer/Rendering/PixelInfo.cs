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
}
