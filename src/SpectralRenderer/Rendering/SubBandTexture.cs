using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Textures;

namespace SpectralRenderer.Rendering;

/// <summary>
/// A spectral texture on the path tracer's sub-band grid (<see cref="SubBandGrid"/>): texel (x, y)'s value on sub-band f is
/// the exact mean over f of its tabulated spectrum — the projection <see cref="SubBandGrid.Resample"/> makes of a plain
/// spectrum. A mean is linear in the texel's samples, so the projection is one sub-band × sample matrix, each column the
/// mean of a sample's tent function, applied to every texel once at load. Mip levels and the filtered lookup are
/// <see cref="TexelLevels"/>'; one copy shared by every thread, a lookup writes into the caller's scratch.
/// </summary>
internal sealed class SubBandTexture : TexelLevels
{
    public SubBandTexture(TextureBinding binding, SubBandGrid grid)
        : base(binding.Texture.Source, binding.Texture.Width, binding.Texture.Height, grid.Padded, binding.Transform)
    {
        var tex = binding.Texture;
        var hats = Hats(tex);
        int rows = grid.Count, samples = tex.Samples;
        var m = new double[rows, samples];
        for (int f = 0; f < rows; f++)
            for (int j = 0; j < samples; j++) m[f, j] = hats[j].Mean(grid.Lower[f], grid.Upper[f]);
        // The texture streamed a block of rows at a time (a file's cube is never held whole), each block's rows in parallel.
        tex.ForEachBlock((y0, count, block) => Parallel.For(0, count, r =>
        {
            for (int x = 0; x < tex.Width; x++)
            {
                var s = block.AsSpan((r * tex.Width + x) * samples, samples);
                var t = Texel(0, x, y0 + r);   // level 0; the padding stays 0
                for (int f = 0; f < rows; f++)
                {
                    double sum = 0;
                    for (int j = 0; j < samples; j++) sum += m[f, j] * s[j];
                    t[f] = (float)sum;
                }
            }
        }));
        BuildMips();
    }

    /// <summary>
    /// Bytes the path tracer's sub-band textures of <paramref name="scene"/> take (the pre-render memory check): per textured
    /// diffuse, specular or emission, its texels with their mip levels × the padded sub-bands of a grid <paramref name="gridWidth"/> nm
    /// wide, once for all threads.
    /// </summary>
    public static long Bytes(Scene scene, double gridWidth)
    {
        var textures = scene.Materials.SelectMany(m => new[] { m.DiffuseTexture, m.SpecularTexture, m.Emission?.Texture })
            .OfType<TextureBinding>().ToList();
        if (textures.Count == 0) return 0;
        int padded = new SubBandGrid(scene, gridWidth).Padded;
        return textures.Sum(t => TexelsWithMips(t.Texture.Width, t.Texture.Height) * padded * sizeof(float));
    }

    /// <summary>The texture at <paramref name="uv"/> for a footprint <paramref name="width"/> wide (uv units) into <paramref name="dst"/>:
    /// Σ weight·texel.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public void Filter(Vector2 uv, float width, Span<float> dst)
    {
        Lookup(uv, width, out var taps);
        var d = MemoryMarshal.Cast<float, Vector<float>>(dst[..Stride]);
        for (int k = 0; k < taps.Count; k++)
        {
            var src = MemoryMarshal.Cast<float, Vector<float>>(Tap(in taps, k));
            var w = new Vector<float>(taps.Weight[k]);
            if (k == 0) for (int i = 0; i < d.Length; i++) d[i] = src[i] * w;
            else for (int i = 0; i < d.Length; i++) d[i] += src[i] * w;
        }
        if (taps.Count == 0) dst[..Stride].Clear();
    }
}
