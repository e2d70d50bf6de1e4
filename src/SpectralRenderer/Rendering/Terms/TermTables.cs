using SpectralRenderer.Color;
using SpectralRenderer.Scenes;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.Terms;

/// <summary>What <see cref="TermTables.Textures"/> holds per texel.</summary>
public enum TexelContent { Tables, Samples, None }

/// <summary>
/// The spectral factors of eq. 2, precomputed once per scene: every term is a scalar (geometry) times a light
/// spectrum times a material spectrum, so its band values are the scalar times the band means of the product
/// E_k·m and its colour the scalar times κ∫x̄·E_k·m dλ — both integrated exactly on the piecewise-linear tables
/// (<see cref="Colorimeter.ProjectProduct"/>, <see cref="Colorimeter.XyzOfProduct"/>; band products under the
/// weighted and paper schemes). Each table is padded: bands, then X, Y, Z in the <see cref="SpectralMath.ColourLanes"/>.
/// The radiometry's constant factors are folded in: physical gives the diffuse lobe 1/π and the specular lobe the
/// energy normalisation of its model.
/// </summary>
public sealed class TermTables
{
    readonly int _materials;

    /// <param name="texels">What the textured materials' texels hold: their per-light tables (a render), their own samples
    /// (the per-light transfer, <see cref="TexturedTerms.SamplesOf"/>), or nothing (a relight: it forms a textured term from
    /// the recorded samples, <see cref="TransferComponent.TexelColumns"/>).</param>
    public TermTables(Scene scene, TexelContent texels = TexelContent.Tables)
    {
        var cm = scene.Colorimeter;
        int bands = scene.Bands, padded = scene.PaddedBands;
        var lights = scene.Lights;
        var materials = scene.Materials;
        _materials = materials.Count;
        bool physical = scene.Radiometry == Radiometry.Physical;
        Diffuse = new float[lights.Count * _materials][];
        Specular = new float[Diffuse.Length][];
        Ambient = new float[Diffuse.Length][];
        GlobalAmbient = new float[_materials][];
        for (int m = 0; m < _materials; m++)
        {
            var mat = materials[m];
            double specNorm = physical ? mat.Model.EnergyNormalisation(mat.Shininess) : 1;
            GlobalAmbient[m] = Product(scene, scene.GlobalAmbient, mat.Ambient, 1);
            for (int k = 0; k < lights.Count; k++)
            {
                Diffuse[k * _materials + m] = Product(scene, lights[k].Intensity, mat.Diffuse, physical ? 1 / Math.PI : 1);
                if (mat.Fluorescence is { } fl)   // the diffuse term is the re-radiation matrix applied to the light
                    FluorescentTerms.AddShift(scene, Diffuse[k * _materials + m], lights[k].Intensity, fl, physical ? 1 / Math.PI : 1);
                Specular[k * _materials + m] = Product(scene, lights[k].Intensity, mat.Specular, specNorm);
                Ambient[k * _materials + m] = Product(scene, lights[k].Ambient, mat.Ambient, 1);
            }
        }
        Background = Single(scene, scene.Background);
        Mirror = new float[_materials][];
        Transmit = new float[_materials][];
        MirrorColoured = new bool[_materials];
        TransmitColoured = new bool[_materials];
        for (int m = 0; m < _materials; m++)
        {
            (Mirror[m], MirrorColoured[m]) = Weight(materials[m].Mirror, bands, padded);
            (Transmit[m], TransmitColoured[m]) = Weight(materials[m].Transmit, bands, padded);
        }
        Textures = texels == TexelContent.None ? null : TextureTables.For(scene, texels == TexelContent.Samples);
    }

    /// <summary>The textured materials' per-texel tables, or null when no material is textured.</summary>
    public TextureTables? Textures { get; }

    /// <summary>I_k ⊙ m_diff (× 1/π physical), index light·M + material.</summary>
    public float[][] Diffuse { get; }
    /// <summary>I_k ⊙ m_spec (× the lobe's energy normalisation physical).</summary>
    public float[][] Specular { get; }
    /// <summary>I_amb,k ⊙ m_amb.</summary>
    public float[][] Ambient { get; }
    /// <summary>a_glob ⊙ m_amb, per material.</summary>
    public float[][] GlobalAmbient { get; }
    /// <summary>The background radiance with its colour lanes.</summary>
    public float[] Background { get; }
    /// <summary>k_r and k_t as weights on an incoming radiance: their colour lanes hold the weight when it is the same in every
    /// band.</summary>
    public float[][] Mirror { get; }
    public float[][] Transmit { get; }
    /// <summary>True when k_r (k_t) varies over the bands: then the colour lanes of what it weights cannot be exact.</summary>
    public bool[] MirrorColoured { get; }
    public bool[] TransmitColoured { get; }

    public int Index(int light, int material) => light * _materials + material;

    /// <summary>The padded table of the radiance a ⊙ b · factor: exact band means of the product and its XYZ when both spectra are
    /// known.</summary>
    static float[] Product(Scene scene, float[] a, float[] b, double factor)
    {
        var cm = scene.Colorimeter;
        int n = scene.Bands;
        var t = new float[scene.PaddedBands];
        if (!SpectralMath.Any(a) || !SpectralMath.Any(b)) return t;
        double[] bands;
        Xyz xyz;
        if (scene.Spectra.TryGetValue(a, out var sa) && scene.Spectra.TryGetValue(b, out var sb))
        {
            bands = cm.ProjectProduct(sa, sb);
            xyz = cm.XyzOfProduct(sa, sb);
        }
        else
        {
            bands = new double[n];
            for (int i = 0; i < n; i++) bands[i] = (double)a[i] * b[i];
            xyz = cm.ToXyz(bands);
        }
        for (int i = 0; i < n; i++) t[i] = (float)(bands[i] * factor);
        t[n] = (float)(xyz.X * factor); t[n + 1] = (float)(xyz.Y * factor); t[n + 2] = (float)(xyz.Z * factor);
        return t;
    }

    /// <summary>A radiance given alone (the background): its band values and the XYZ of its spectrum.</summary>
    static float[] Single(Scene scene, float[] a)
    {
        var cm = scene.Colorimeter;
        int n = scene.Bands;
        var t = new float[scene.PaddedBands];
        a.AsSpan(0, n).CopyTo(t);
        if (!SpectralMath.Any(a)) return t;
        Xyz xyz;
        if (scene.Spectra.TryGetValue(a, out var s))
        {
            var bands = cm.Scheme == BandIntegration.Exact ? BandProjection.Means(s, scene.Grid) : cm.Project(s);
            for (int i = 0; i < n; i++) t[i] = (float)bands[i];
            xyz = cm.Scheme == BandIntegration.Exact ? cm.OfProduct(s, null) : cm.ToXyz(bands);
        }
        else xyz = cm.ToXyz((ReadOnlySpan<float>)a.AsSpan(0, n));
        t[n] = (float)xyz.X; t[n + 1] = (float)xyz.Y; t[n + 2] = (float)xyz.Z;
        return t;
    }

    static (float[], bool) Weight(float[] w, int bands, int padded)
    {
        var t = new float[padded];
        w.AsSpan(0, bands).CopyTo(t);
        bool constant = true;
        for (int i = 1; i < bands; i++) constant &= w[i] == w[0];
        if (constant) for (int i = bands; i < bands + SpectralMath.ColourLanes; i++) t[i] = w[0];
        return (t, !constant);
    }
}
