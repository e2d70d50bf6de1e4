using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Textures;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.Terms;

/// <summary>
/// Which term of eq. 2 a component is: light k through the diffuse or specular lobe (these follow the light's spectrum),
/// light k's own ambient spectrum I_amb,k·m_amb, the global ambient a_glob·m_amb, or the background radiance.
/// </summary>
public enum TransferLobe { Diffuse, Specular, Ambient, GlobalAmbient, Background }

/// <summary>
/// One spectral component of a pixel's radiance: a term of eq. 2 (<see cref="Lobe"/>) of light <see cref="Light"/>
/// (−1 for the global ambient and the background) at material <see cref="Material"/> (−1 for the background), reached
/// from the camera through the mirror (k_r) and transmission (k_t) weights of the materials in <see cref="Chain"/>
/// (first bounce first). Its band values are P_b = E_b · m_b · Π k_chain,b with E the light's spectrum × intensity
/// (diffuse, specular), its ambient spectrum, or a_glob, and m the lobe's reflectance — the products eq. 2 and the
/// Whitted recursion form in every band. A component reached through a dispersive material carries one band only
/// (<see cref="Band"/> ≥ 0): there each band follows its own path, as the integrator traces it.
/// </summary>
public sealed record TransferComponent(int Light, TransferLobe Lobe, int Material, (int Material, bool Transmit)[] Chain)
{
    /// <summary>The one band (0-based) this component reaches, after a dispersive split; −1 for all bands.</summary>
    public int Band { get; init; } = -1;

    /// <summary>Does the component follow light k's spectrum and intensity (diffuse and specular terms)?</summary>
    public bool FollowsLight => Lobe is TransferLobe.Diffuse or TransferLobe.Specular;

    public static string LobeName(TransferLobe l) => l switch
    {
        TransferLobe.Diffuse => "diffuse",
        TransferLobe.Specular => "specular",
        TransferLobe.Ambient => "ambient",
        TransferLobe.GlobalAmbient => "global-ambient",
        _ => "background",
    };

    public static TransferLobe ParseLobe(string s) => s switch
    {
        "diffuse" => TransferLobe.Diffuse,
        "specular" => TransferLobe.Specular,
        "ambient" => TransferLobe.Ambient,
        "global-ambient" => TransferLobe.GlobalAmbient,
        "background" => TransferLobe.Background,
        _ => throw new InputException("lights.json", $"unknown component lobe '{s}'",
            "the light-transfer files are damaged: render the folder again"),
    };

    /// <summary>A stable text key such as <c>0:diffuse:2</c>, <c>1:specular:3&lt;mirror:1</c> or, for band 5 only,
    /// <c>0:diffuse:2&lt;transmit:0@5</c>.</summary>
    public string Key => $"{Light}:{LobeName(Lobe)}:{Material}" +
        string.Concat(Chain.Reverse().Select(c => $"<{(c.Transmit ? "transmit" : "mirror")}:{c.Material}"))
            + (Band >= 0 ? $"@{Band + 1}" : "");

    /// <summary>
    /// P into <paramref name="dst"/> (padded: the bands, then X, Y, Z in the colour lanes): the scene's term table of this
    /// component (<see cref="TermTables"/>: exact band means of E·m and κ∫x̄E·m dλ, with the radiometry's constants) times
    /// the mirror and transmission weights along the chain, as the integrator multiplies them.
    /// </summary>
    public void BandValues(TermTables tables, Span<float> dst)
    {
        ReadOnlySpan<float> t = Lobe switch
        {
            TransferLobe.Diffuse => tables.Diffuse[tables.Index(Light, Material)],
            TransferLobe.Specular => tables.Specular[tables.Index(Light, Material)],
            TransferLobe.Ambient => tables.Ambient[tables.Index(Light, Material)],
            TransferLobe.GlobalAmbient => tables.GlobalAmbient[Material],
            _ => tables.Background,
        };
        t.CopyTo(dst);
        foreach (var (cm, tr) in Chain)
        {
            var w = tr ? tables.Transmit[cm] : tables.Mirror[cm];
            for (int b = 0; b < dst.Length; b++) dst[b] *= w[b];
        }
        if (Band >= 0)
        {   // One band only; its colour is eq. 3 on the band values (such pixels take the renderer's colour fallback).
            float v = dst[Band];
            dst.Clear();
            dst[Band] = v;
        }
    }

    /// <summary>
    /// The texture whose texels this component's term takes (issue 26): the material's diffuse texture for its diffuse term
    /// and, when m_amb is that texture, its ambient terms; its specular texture for its specular term. Null: a spectrum.
    /// </summary>
    public SpectralTexture? Texture(Scene scene)
    {
        if (Material < 0) return null;
        var m = scene.Materials[Material];
        return Lobe switch
        {
            TransferLobe.Diffuse => m.DiffuseTexture?.Texture,
            TransferLobe.Specular => m.SpecularTexture?.Texture,
            TransferLobe.Ambient or TransferLobe.GlobalAmbient => TextureTables.AmbientIsTexture(m) ? m.DiffuseTexture!.Texture : null,
            _ => null,
        };
    }

    /// <summary>
    /// A textured component's P as a matrix (null when it is not textured, <see cref="Texture"/>): column i (at i · padded)
    /// the band values and XYZ of E ⊙ tent_i × the lobe's constant (<see cref="TexturedTerms.MatrixOf"/>, the products the
    /// render's texel tables are made of), and <paramref name="constant"/> the part the same at every texel (a fluorescent
    /// diffuse term's shift, <see cref="FluorescentTerms.AddShift"/>), both times the chain's weights as
    /// <see cref="BandValues"/> multiplies them. A pixel's entry is then Σ_i V_i · column_i + F · constant, with V the
    /// recorded sum of F × the filtered texel samples.
    /// </summary>
    public double[]? TexelColumns(Scene scene, TermTables tables, out double[] constant)
    {
        int padded = scene.PaddedBands, rows = scene.Bands + SpectralMath.ColourLanes;
        constant = new double[padded];
        if (Texture(scene) is not { } texture) return null;
        var mat = scene.Materials[Material];
        bool physical = scene.Radiometry == Radiometry.Physical;
        var (light, factor) = Lobe switch
        {
            TransferLobe.Diffuse => (scene.Lights[Light].Intensity, physical ? 1 / Math.PI : 1),
            TransferLobe.Specular => (scene.Lights[Light].Intensity, physical ? mat.Model.EnergyNormalisation(mat.Shininess) : 1),
            TransferLobe.Ambient => (scene.Lights[Light].Ambient, 1.0),
            _ => (scene.GlobalAmbient, 1.0),
        };
        var m = TexturedTerms.MatrixOf(scene, texture, light, factor);
        int samples = texture.Samples;
        var columns = new double[samples * padded];
        for (int i = 0; i < samples; i++)
            for (int r = 0; r < rows; r++) columns[i * padded + r] = m[r, i];
        if (Lobe == TransferLobe.Diffuse && mat.Fluorescence is { HasShift: true } fl)
        {
            var shift = new float[padded];
            FluorescentTerms.AddShift(scene, shift, light, fl, factor);
            for (int r = 0; r < rows; r++) constant[r] = shift[r];
        }
        foreach (var (cm, tr) in Chain)
        {
            var w = tr ? tables.Transmit[cm] : tables.Mirror[cm];
            for (int r = 0; r < padded; r++)
            {
                constant[r] *= w[r];
                for (int i = 0; i < samples; i++) columns[i * padded + r] *= w[r];
            }
        }
        if (Band >= 0)
            for (int r = 0; r < padded; r++)
                if (r != Band)
                {
                    constant[r] = 0;
                    for (int i = 0; i < samples; i++) columns[i * padded + r] = 0;
                }
        return columns;
    }

    /// <summary>Does the chain pass a mirror or transmittance that varies over the bands, or a dispersive split (so the colour lanes cannot
    /// be exact)?</summary>
    public bool Coloured(TermTables tables) =>
        Band >= 0 || Chain.Any(c => c.Transmit ? tables.TransmitColoured[c.Material] : tables.MirrorColoured[c.Material]);
}
