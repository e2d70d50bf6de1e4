using System.Numerics;
using System.Runtime.CompilerServices;
using SpectralRenderer.Color;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Textures;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Rendering;

/// <summary>
/// The textured terms of eq. 2 for every material with a diffuse texture: per texel and light the table of
/// I_k ⊙ m_diff (band means and XYZ lanes, × 1/π physical), and when m_amb is the texture too, a_glob ⊙ m_amb and
/// I_amb,k ⊙ m_amb — the same exact products <see cref="TermTables"/> makes for a plain spectrum, for the texel's own
/// spectrum. Band means and colour are linear in the texel's samples, so each light's product is a matrix (bands + XYZ)
/// × samples, built once by projecting the tent function of each sample; a texel's table is that matrix times its
/// samples. Mip levels (Williams 1983) average the tables by area (halving each side, a texel's share by overlap, so
/// every level keeps the mean); a lookup blends the two levels around the footprint's size, bilinear in each.
/// </summary>
public sealed class TextureTables
{
    TextureTables(TexturedTerms?[] of) { Of = of; }

    /// <summary>Per material, its textured terms or null.</summary>
    public TexturedTerms?[] Of { get; }

    /// <summary>The tables of <paramref name="scene"/>'s textured materials, or null when it has none.</summary>
    public static TextureTables? For(Scene scene)
    {
        if (!scene.Materials.Any(m => m.DiffuseTexture is not null)) return null;
        var of = new TexturedTerms?[scene.Materials.Count];
        for (int m = 0; m < of.Length; m++)
        {
            var mat = scene.Materials[m];
            if (mat.DiffuseTexture is not { } binding) continue;
            bool ambient = ReferenceEquals(mat.Ambient, mat.Diffuse);
            of[m] = new TexturedTerms(scene, binding, ambient);
            if (mat.Fluorescence is { HasShift: true } fl) of[m]!.AddShift(scene, fl);   // the texels are its diagonal
        }
        return new TextureTables(of);
    }

    /// <summary>Bytes the tables of <paramref name="scene"/> take (the pre-render memory check).</summary>
    public static long Bytes(Scene scene)
    {
        long bytes = 0;
        foreach (var m in scene.Materials)
            if (m.DiffuseTexture is { } b)
                bytes += TexturedTerms.TexelsWithMips(b.Texture.Width, b.Texture.Height) * (1 + 2L * scene.Lights.Count) * scene.PaddedBands * sizeof(float);
        return bytes;
    }
}

/// <summary>One material's textured tables: slot 0 a_glob ⊙ m_amb, slot 1 + k I_amb,k ⊙ m_amb, slot 1 + L + k I_k ⊙ m_diff.</summary>
public sealed class TexturedTerms : TexelLevels
{
    readonly int _padded;

    public TexturedTerms(Scene scene, TextureBinding binding, bool ambient)
        : base(binding.Texture.Source, binding.Texture.Width, binding.Texture.Height, (1 + 2 * scene.Lights.Count) * scene.PaddedBands, binding.Transform)
    {
        var tex = binding.Texture;
        _padded = scene.PaddedBands;
        int lights = scene.Lights.Count;
        Slots = 1 + 2 * lights;
        Ambient = ambient;

        // Per slot the (bands + XYZ) × samples matrix of the product with that slot's light.
        bool physical = scene.Radiometry == Radiometry.Physical;
        var matrices = new double[Slots][,];
        var hats = Hats(tex);
        matrices[0] = ambient ? Matrix(scene, scene.GlobalAmbient, hats, 1) : Zero(scene, hats.Length);
        for (int k = 0; k < lights; k++)
        {
            matrices[1 + k] = ambient ? Matrix(scene, scene.Lights[k].Ambient, hats, 1) : Zero(scene, hats.Length);
            matrices[1 + lights + k] = Matrix(scene, scene.Lights[k].Intensity, hats, physical ? 1 / Math.PI : 1);
        }
        int rows = scene.Bands + SpectralMath.ColourLanes, samples = tex.Samples, slots = Slots, padded = _padded;
        var data = Data;
        Parallel.For(0, tex.Height, y =>
        {
            for (int x = 0; x < tex.Width; x++)
            {
                var s = tex.Texel(x, y);
                for (int slot = 0; slot < slots; slot++)
                {
                    var m = matrices[slot];
                    var t = data.AsSpan(((y * tex.Width + x) * slots + slot) * padded, padded);
                    for (int r = 0; r < rows; r++)
                    {
                        double sum = 0;
                        for (int j = 0; j < samples; j++) sum += m[r, j] * s[j];
                        t[r] = (float)sum;
                    }
                }
            }
        });
        BuildMips();
    }

    /// <summary>Slots per texel (1 + 2 × lights), each padded bands long.</summary>
    public int Slots { get; }
    /// <summary>Is m_amb the texture (it defaulted to m_diff)?</summary>
    public bool Ambient { get; }

    /// <summary>The offset of <paramref name="slot"/> within a texel's tables.</summary>
    public int SlotOffset(int slot) => slot * _padded;

    /// <summary>
    /// A fluorescent material's shifted part beside texels that are its reflective diagonal: the same at every texel, so each
    /// light's I_k ⊗ shift (<see cref="FluorescentTerms.AddShift"/>, × 1/π physical) is added to that light's diffuse slot of
    /// every texel of every level (a level's texels are weighted means, so a constant passes through them unchanged).
    /// </summary>
    internal void AddShift(Scene scene, ReradiationMatrix matrix)
    {
        int lights = scene.Lights.Count, texels = Data.Length / Stride;
        double factor = scene.Radiometry == Radiometry.Physical ? 1 / Math.PI : 1;
        var shift = new float[_padded];
        for (int k = 0; k < lights; k++)
        {
            Array.Clear(shift);
            FluorescentTerms.AddShift(scene, shift, scene.Lights[k].Intensity, matrix, factor);
            int offset = SlotOffset(1 + lights + k);
            for (int t = 0; t < texels; t++)
            {
                var d = Data.AsSpan(t * Stride + offset, _padded);
                for (int r = 0; r < d.Length; r++) d[r] += shift[r];
            }
        }
    }

    /// <summary>The tent functions of the texture's samples (1 at sample j, 0 at the others, the texture's extrapolation).</summary>
    internal static TabulatedSpectrum[] Hats(SpectralTexture tex)
    {
        var hats = new TabulatedSpectrum[tex.Samples];
        for (int j = 0; j < hats.Length; j++)
        {
            var v = new double[tex.Samples];
            v[j] = 1;
            hats[j] = new TabulatedSpectrum($"{tex.Source} sample {j}", tex.Wavelengths, v, tex.Extrapolation);
        }
        return hats;
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
