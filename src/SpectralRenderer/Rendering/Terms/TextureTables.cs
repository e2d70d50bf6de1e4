using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Color;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Textures;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering.Terms;

/// <summary>
/// The textured terms of eq. 2 for every material with a texture on its diffuse or specular lobe, each lobe its own
/// tables (<see cref="TexturedTerms"/>): per texel and light I_k ⊙ m_diff (× 1/π physical) and, when m_amb is the
/// diffuse texture too, a_glob ⊙ m_amb and I_amb,k ⊙ m_amb; per texel and light I_k ⊙ m_spec (× the lobe's energy
/// normalisation physical) — band means and XYZ lanes, the same exact products <see cref="TermTables"/> makes for a plain
/// spectrum, for the texel's own spectrum. Band means and colour are linear in the texel's samples, so each light's product
/// is a matrix (bands + XYZ) × samples, built once by projecting the tent function of each sample; a texel's table is that
/// matrix times its samples. Mip levels (Williams 1983) average the tables by area (halving each side, a texel's share by
/// overlap, so every level keeps the mean); a lookup blends the two levels around the footprint's size, bilinear in each.
/// </summary>
public sealed class TextureTables
{
    TextureTables(TexturedTerms?[] diffuse, TexturedTerms?[] specular)
    {
        Diffuse = diffuse;
        Specular = specular;
        Textured = new bool[diffuse.Length];
        for (int m = 0; m < diffuse.Length; m++) Textured[m] = diffuse[m] is not null || specular[m] is not null;
    }

    /// <summary>Per material, the terms of its diffuse texture (and of m_amb when that is the texture), or null.</summary>
    public TexturedTerms?[] Diffuse { get; }
    /// <summary>Per material, the terms of its specular texture, or null.</summary>
    public TexturedTerms?[] Specular { get; }
    /// <summary>Per material, is any of its lobes textured?</summary>
    public bool[] Textured { get; }

    /// <summary>The tables of <paramref name="scene"/>'s textured materials, or null when it has none.</summary>
    /// <param name="samples">Each texel's own samples instead of its per-light tables (<see cref="TexturedTerms.Samples"/>):
    /// what the per-light transfer records, so that a relight can form the tables of new lights.</param>
    public static TextureTables? For(Scene scene, bool samples = false)
    {
        if (!scene.Materials.Any(m => m.DiffuseTexture is not null || m.SpecularTexture is not null)) return null;
        var diffuse = new TexturedTerms?[scene.Materials.Count];
        var specular = new TexturedTerms?[diffuse.Length];
        for (int m = 0; m < diffuse.Length; m++)
        {
            var mat = scene.Materials[m];
            bool ambient = AmbientIsTexture(mat);
            if (samples)
            {
                if (mat.DiffuseTexture is { } ds) diffuse[m] = TexturedTerms.SamplesOf(ds, TexturedLobe.Diffuse, ambient);
                if (mat.SpecularTexture is { } ss) specular[m] = TexturedTerms.SamplesOf(ss, TexturedLobe.Specular, false);
                continue;
            }
            if (mat.DiffuseTexture is { } d) diffuse[m] = TexturedTerms.ForDiffuse(scene, d, ambient);
            // the texels are its diagonal
            if (mat.Fluorescence is { HasShift: true } fl && diffuse[m] is { } texels) texels.AddShift(scene, fl);
            if (mat.SpecularTexture is { } s) specular[m] = TexturedTerms.ForSpecular(scene, s, mat);
        }
        return new TextureTables(diffuse, specular);
    }

    /// <summary>Is <paramref name="material"/>'s m_amb its diffuse texture (m_amb defaulted to m_diff)?</summary>
    public static bool AmbientIsTexture(Material material) =>
        material.DiffuseTexture is not null && ReferenceEquals(material.Ambient, material.Diffuse);

    /// <summary>Bytes the tables of <paramref name="scene"/> take (the pre-render memory check): every textured lobe's.</summary>
    public static long Bytes(Scene scene)
    {
        long bytes = 0;
        int lights = scene.Lights.Count;
        long Tables(TextureBinding b, TexturedLobe lobe) =>
            TexturedTerms.TexelsWithMips(b.Texture.Width, b.Texture.Height) * TexturedTerms.SlotsOf(lobe, lights)
            * scene.PaddedBands * sizeof(float);
        foreach (var m in scene.Materials)
        {
            if (m.DiffuseTexture is { } d) bytes += Tables(d, TexturedLobe.Diffuse);
            if (m.SpecularTexture is { } s) bytes += Tables(s, TexturedLobe.Specular);
        }
        return bytes;
    }
}

/// <summary>The lobe of eq. 2 a texture stands on.</summary>
public enum TexturedLobe { Diffuse, Specular }

/// <summary>
/// One textured lobe's tables per texel, each slot a padded table. Diffuse: slot 0 a_glob ⊙ m_amb, slot 1 + k
/// I_amb,k ⊙ m_amb (zero unless m_amb is the texture), slot 1 + L + k I_k ⊙ m_diff. Specular: slot k I_k ⊙ m_spec.
/// </summary>
public sealed class TexturedTerms : TexelLevels
{
    readonly int _padded, _lights;

    TexturedTerms(Scene scene, TextureBinding binding, TexturedLobe lobe, bool ambient, double[][,] matrices)
        : base(binding.Texture.Source, binding.Texture.Width, binding.Texture.Height, matrices.Length * scene.PaddedBands,
            binding.Transform)
    {
        var tex = binding.Texture;
        _padded = scene.PaddedBands;
        _lights = scene.Lights.Count;
        Lobe = lobe;
        Slots = matrices.Length;
        Ambient = ambient;
        int lanes = scene.Bands + SpectralMath.ColourLanes, samples = tex.Samples, slots = Slots, padded = _padded;
        // The texture streamed a block of rows at a time (a file's cube is never held whole), each block's rows in parallel.
        tex.ForEachBlock((y0, rows, block) => Parallel.For(0, rows, r =>
        {
            for (int x = 0; x < tex.Width; x++)
            {
                var s = block.AsSpan((r * tex.Width + x) * samples, samples);
                var texel = Texel(0, x, y0 + r);
                for (int slot = 0; slot < slots; slot++)
                {
                    var m = matrices[slot];
                    var t = texel.Slice(slot * padded, padded);
                    for (int i = 0; i < lanes; i++)
                    {
                        double sum = 0;
                        for (int j = 0; j < samples; j++) sum += m[i, j] * s[j];
                        t[i] = (float)sum;
                    }
                }
            }
        }));
        BuildMips();
    }

    /// <summary>
    /// A texture's own samples with their mip levels (stride = the texture's sample count, one slot): the same levels and
    /// the same lookup as its tables, so a tap's texel holds the samples whose products the tables are. Eq. 2's tables are
    /// linear in the samples, so Σ w·table(texel) = M · Σ w·samples(texel), M the light's (bands + XYZ) × samples matrix
    /// (<see cref="MatrixOf"/>): what the per-light transfer records per pixel and a relight multiplies by new lights' M.
    /// </summary>
    public static TexturedTerms SamplesOf(TextureBinding binding, TexturedLobe lobe, bool ambient) => new(binding, lobe, ambient);

    TexturedTerms(TextureBinding binding, TexturedLobe lobe, bool ambient)
        : base(binding.Texture.Source, binding.Texture.Width, binding.Texture.Height, binding.Texture.Samples, binding.Transform)
    {
        Lobe = lobe;
        Slots = 1;
        Ambient = ambient;
        Samples = true;
        var tex = binding.Texture;
        int samples = tex.Samples;
        // Level 0's texels are the texture's samples, streamed a block of rows at a time as the tables are.
        tex.ForEachBlock((y0, rows, block) =>
        {
            for (int r = 0; r < rows; r++)
                for (int x = 0; x < tex.Width; x++)
                    block.AsSpan((r * tex.Width + x) * samples, samples).CopyTo(Texel(0, x, y0 + r));
        });
        BuildMips();
    }

    /// <summary>Do the texels hold the texture's samples (<see cref="SamplesOf"/>) rather than per-light tables?</summary>
    public bool Samples { get; }

    /// <summary>The (bands + XYZ) × samples matrix of <paramref name="light"/> ⊙ the texture's tent functions × factor: a texel's
    /// table of that light is this matrix times its samples (<see cref="ForDiffuse"/>, <see cref="ForSpecular"/>).</summary>
    public static double[,] MatrixOf(Scene scene, SpectralTexture texture, float[] light, double factor) =>
        Matrix(scene, light, Hats(texture), factor);

    /// <summary>The diffuse lobe's tables (per slot the (bands + XYZ) × samples matrix of the product with that slot's light);
    /// the ambient slots hold a_glob ⊙ texel and I_amb,k ⊙ texel when <paramref name="ambient"/> (m_amb is the texture).</summary>
    public static TexturedTerms ForDiffuse(Scene scene, TextureBinding binding, bool ambient)
    {
        int lights = scene.Lights.Count;
        bool physical = scene.Radiometry == Radiometry.Physical;
        var matrices = new double[SlotsOf(TexturedLobe.Diffuse, lights)][,];
        var hats = Hats(binding.Texture);
        matrices[0] = ambient ? Matrix(scene, scene.GlobalAmbient, hats, 1) : Zero(scene, hats.Length);
        for (int k = 0; k < lights; k++)
        {
            matrices[1 + k] = ambient ? Matrix(scene, scene.Lights[k].Ambient, hats, 1) : Zero(scene, hats.Length);
            matrices[1 + lights + k] = Matrix(scene, scene.Lights[k].Intensity, hats, physical ? 1 / Math.PI : 1);
        }
        return new TexturedTerms(scene, binding, TexturedLobe.Diffuse, ambient, matrices);
    }

    /// <summary>The specular lobe's tables of <paramref name="material"/>: per light I_k ⊙ texel, times the specular model's
    /// energy normalisation under physical radiometry (as <see cref="TermTables.Specular"/>).</summary>
    public static TexturedTerms ForSpecular(Scene scene, TextureBinding binding, Material material)
    {
        int lights = scene.Lights.Count;
        double norm = scene.Radiometry == Radiometry.Physical ? material.Model.EnergyNormalisation(material.Shininess) : 1;
        var matrices = new double[SlotsOf(TexturedLobe.Specular, lights)][,];
        var hats = Hats(binding.Texture);
        for (int k = 0; k < lights; k++) matrices[k] = Matrix(scene, scene.Lights[k].Intensity, hats, norm);
        return new TexturedTerms(scene, binding, TexturedLobe.Specular, false, matrices);
    }

    /// <summary>Slots per texel of <paramref name="lobe"/> with <paramref name="lights"/> lights: 1 + 2 × lights diffuse,
    /// lights specular.</summary>
    public static int SlotsOf(TexturedLobe lobe, int lights) => lobe == TexturedLobe.Diffuse ? 1 + 2 * lights : lights;

    /// <summary>The lobe the texture stands on.</summary>
    public TexturedLobe Lobe { get; }
    /// <summary>Slots per texel (<see cref="SlotsOf"/>), each padded bands long.</summary>
    public int Slots { get; }
    /// <summary>Is m_amb the texture (a diffuse texture whose material's m_amb defaulted to m_diff)?</summary>
    public bool Ambient { get; }

    /// <summary>The offset of <paramref name="slot"/> within a texel's tables.</summary>
    public int SlotOffset(int slot) => slot * _padded;

    /// <summary>The slot of light <paramref name="light"/>'s direct term (I_k ⊙ the lobe's texel).</summary>
    public int LightSlot(int light) => Lobe == TexturedLobe.Diffuse ? 1 + _lights + light : light;

    /// <summary>
    /// A fluorescent material's shifted part beside texels that are its reflective diagonal: the same at every texel, so each
    /// light's I_k ⊗ shift (<see cref="FluorescentTerms.AddShift"/>, × 1/π physical) is added to that light's diffuse slot of
    /// every texel of every level (a level's texels are weighted means, so a constant passes through them unchanged).
    /// </summary>
    internal void AddShift(Scene scene, ReradiationMatrix matrix)
    {
        int lights = scene.Lights.Count;
        double factor = scene.Radiometry == Radiometry.Physical ? 1 / Math.PI : 1;
        var shift = new float[_padded];
        for (int k = 0; k < lights; k++)
        {
            Array.Clear(shift);
            FluorescentTerms.AddShift(scene, shift, scene.Lights[k].Intensity, matrix, factor);
            int offset = SlotOffset(LightSlot(k)), stride = Stride, padded = _padded;
            ForEachChunk(chunk =>
            {
                for (int t = 0; t < chunk.Length; t += stride)
                {
                    var d = chunk.Slice(t + offset, padded);
                    for (int r = 0; r < d.Length; r++) d[r] += shift[r];
                }
            });
        }
    }

    static double[,] Zero(Scene scene, int samples) => new double[scene.Bands + SpectralMath.ColourLanes, samples];

    /// <summary>
    /// Column j: the band values and XYZ of light ⊙ tent_j × factor, as <see cref="TermTables"/> makes them for a material
    /// spectrum — exact (<see cref="Colorimeter.ProjectProduct"/>, <see cref="Colorimeter.XyzOfProduct"/>) when the light's
    /// spectrum is known, else the band product and its XYZ.
    /// </summary>
    static double[,] Matrix(Scene scene, float[] light, TabulatedSpectrum[] hats, double factor)
    {
        var cm = scene.Colorimeter;
        int n = scene.Bands;
        var m = new double[n + SpectralMath.ColourLanes, hats.Length];
        if (!SpectralMath.Any(light)) return m;
        bool known = scene.Spectra.TryGetValue(light, out var e);
        for (int j = 0; j < hats.Length; j++)
        {
            double[] bands;
            Xyz xyz;
            if (known)
            {
                bands = cm.ProjectProduct(e!, hats[j]);
                xyz = cm.XyzOfProduct(e!, hats[j]);
            }
            else
            {
                var hatBands = cm.Scheme == BandIntegration.Exact ? BandProjection.Means(hats[j], scene.Grid) : cm.Project(hats[j]);
                bands = new double[n];
                for (int i = 0; i < n; i++) bands[i] = light[i] * hatBands[i];
                xyz = cm.ToXyz(bands);
            }
            for (int i = 0; i < n; i++) m[i, j] = bands[i] * factor;
            m[n, j] = xyz.X * factor; m[n + 1, j] = xyz.Y * factor; m[n + 2, j] = xyz.Z * factor;
        }
        return m;
    }
}
