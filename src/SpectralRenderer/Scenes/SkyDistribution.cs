namespace SpectralRenderer.Scenes;

/// <summary>
/// How a daylight sky's radiance is spread over the directions (<c>"sky": { "type": "daylight", "distribution": … }</c>);
/// the spectrum is the same in every direction (<see cref="Scene.Background"/>), only its scale varies.
/// </summary>
public enum SkyDistribution
{
    /// <summary>The same radiance from every direction a ray escapes in, below the horizon too (CIE 110-1994's uniform sky).</summary>
    Uniform,

    /// <summary>
    /// The CIE standard overcast sky (Moon &amp; Spencer 1942; CIE S 011/E:2003, ISO 15469:2004 sky type 1 in its traditional
    /// form): L(θ) = L_z·(1 + 2 cos θ)/3 at the angle θ from the zenith (<see cref="Scene.Zenith"/>), nothing below the horizon;
    /// <see cref="Scene.Background"/> is the zenith's L_z, three times the horizon's.
    /// </summary>
    CieOvercast,
}
