using System.Buffers.Binary;
using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.PathTracing;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Rendering.Terms;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Scenes.Textures;
using SpectralRenderer.Tests.Scenes;

namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Texel tables in tiles and chunks, textures streamed (issue 26, "large textures streamed or tiled"): the memory check's
/// texture bytes equal the tiles as allocated and as counted here from the texture's size, the bands, the lights, the mip
/// levels and the tile side; with tiles of 4 texels and chunks of a few tiles forced, filtered lookups across tile and
/// chunk boundaries equal bilinear filtering done here on texel spectra projected here (analytic: linear spectra); an
/// ENVI cube read a block of rows at a time in every interleave, byte order and sample type gives the values written.
/// </summary>
public class TiledTexelTests
{
    const int W = 42, H = 26;   // even: a level-1 texel is the plain mean of its 2 × 2; neither level a whole number of tiles of 4

    /// <summary>Texel (x, y)'s spectrum a + b·(λ − 380)/400: its mean over [lo, hi] is its value at the midpoint.</summary>
    static (double A, double B) Linear(int x, int y) =>
        (0.2 + 0.6 * ((x * 7 + y * 13) % 17) / 16.0, 0.3 * ((x * 3 + y * 5) % 11) / 10.0 - 0.15);

    static readonly double[] Wl = Enumerable.Range(0, 45).Select(i => 360.0 + 10 * i).ToArray();   // covers the bands

    static Scene LoadScene(string dir, int lights = 1, bool specular = false)
    {
        var texels = new float[W * H * Wl.Length];
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
            {
                var (a, b) = Linear(x, y);
                for (int j = 0; j < Wl.Length; j++) texels[(y * W + x) * Wl.Length + j] = (float)(a + b * (Wl[j] - 380) / 400);
            }
        SpectralTextureTests.WriteEnvi(Path.Combine(dir, "linear.img"), W, H, Wl, texels);
        var lightList = string.Join(", ", Enumerable.Range(0, lights).Select(k =>
            $$"""{ "type": "directional", "direction": [{{0.1 * k}}, 0, -1], "spectrum": "D65", "intensity": 0.5 }"""));
        var spec = specular ? """, "specular": { "texture": "linear.hdr" }, "shininess": 20""" : "";
        var json = $$"""
            {
              "bands": "380:780:20", "integration": "exact", "radiometry": "paper", "white": "D65",
              "camera": { "position": [0, 0, 9], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40, "width": 64, "height": 48, "spp": 1 },
              "lights": [ {{lightList}} ],
              "objects": [ { "type": "quad", "center": [0, 0, 0], "size": [5, 3],
                "material": { "diffuse": { "texture": "linear.hdr" }{{spec}} } } ],
              "background": 0, "max_depth": 0
            }
            """;
        return SceneLoader.Parse(Encoding.UTF8.GetBytes(json), Path.Combine(dir, "scene.json"));
    }

    /// <summary>Floats of a w × h texture's tables with all mip levels, <paramref name="stride"/> floats per texel, counted tile
    /// by tile (tiles of <paramref name="side"/>, the last of each row and column clipped).</summary>
    static long TileFloats(int w, int h, int stride, int side)
    {
        long floats = 0;
        while (true)
        {
            for (int ty = 0; ty < h; ty += side)
                for (int tx = 0; tx < w; tx += side) floats += (long)Math.Min(side, w - tx) * Math.Min(side, h - ty) * stride;
            if (w == 1 && h == 1) return floats;
            w = Math.Max(1, w / 2); h = Math.Max(1, h / 2);
        }
    }

    static int Padded(int lanes) => (lanes + Vector<float>.Count - 1) / Vector<float>.Count * Vector<float>.Count;

    [Fact]
    public void The_memory_check_states_the_texture_tables_bytes_as_allocated()
    {
        var dir = Reference.TempDir();
        var scene = LoadScene(dir, lights: 3, specular: true);
        // Whitted: per texel, the diffuse lobe 1 + 2·lights slots, the specular lobe one per light, each the 20 bands and
        // X, Y, Z padded to whole SIMD vectors.
        int slot = Padded(20 + 3);
        long expected = 4 * (TileFloats(W, H, (1 + 2 * 3) * slot, TexelLevels.DefaultTileSide)
            + TileFloats(W, H, 3 * slot, TexelLevels.DefaultTileSide));
        var tables = new TermTables(scene).Textures!;
        long allocated = tables.Diffuse[0]!.AllocatedBytes + tables.Specular[0]!.AllocatedBytes;
        Assert.Equal(expected, allocated);
        Assert.Equal(expected, TextureTables.Bytes(scene));
        Assert.Contains(("texture tables", expected), RenderMemory.Estimate(scene, 1));
        // The path tracer: each textured lobe a spectrum on the sub-band grid (its sub-bands and 3 colour lanes, padded).
        var grid = new SubBandGrid(scene, IntegratorSettings.DefaultSpectralGrid);
        long fine = 4 * 2 * TileFloats(W, H, Padded(grid.Count + 3), TexelLevels.DefaultTileSide);
        var binding = scene.Materials[0].DiffuseTexture!;
        Assert.Equal(fine, 2 * new SubBandTexture(binding, grid).AllocatedBytes);
        Assert.Equal(fine, SubBandTexture.Bytes(scene, PathIntegrator.SettingsOf(scene).SpectralGrid));
        Assert.Contains(("texture spectra (fine grid)", fine), RenderMemory.Estimate(scene, 1, integrator: "path"));
    }

    [Fact]
    public void Lookups_across_tile_and_chunk_boundaries_equal_bilinear_filtering_of_the_projected_spectra()
    {
        var dir = Reference.TempDir();
        var scene = LoadScene(dir);
        var grid = new SubBandGrid(scene, IntegratorSettings.DefaultSpectralGrid);
        int stride = Padded(grid.Count + 3);
        SubBandTexture texture;
        TexelLevels.Layout.Value = (4, 3 * 16 * stride);   // tiles of 4 × 4 texels, three to a chunk
        SpectralTexture.BlockOverride.Value = 5 * W * Wl.Length;   // the cube read five rows at a time
        try { texture = new SubBandTexture(scene.Materials[0].DiffuseTexture!, grid); }
        finally { TexelLevels.Layout.Value = null; SpectralTexture.BlockOverride.Value = null; }
        Assert.Equal(4, texture.TileSide);
        Assert.True(texture.Chunks >= 20, $"{texture.Chunks} chunks");
        Assert.Equal(4L * TileFloats(W, H, stride, 4), texture.AllocatedBytes);

        // The reference: level 0 the texel spectra's sub-band means (the midpoint value of a linear spectrum), level 1 each
        // 2 × 2's mean; bilinear with repeat wrap as the uv convention says (row 0 at v = 1, texel centres at +0.5).
        double Level0(int x, int y, int f)
        {
            var (a, b) = Linear(x, y);
            return a + b * ((grid.Lower[f] + grid.Upper[f]) / 2 - 380) / 400;
        }
        double Level1(int x, int y, int f) =>
            (Level0(2 * x, 2 * y, f) + Level0(2 * x + 1, 2 * y, f) + Level0(2 * x, 2 * y + 1, f) + Level0(2 * x + 1, 2 * y + 1, f)) / 4;
        double Bilinear(Func<int, int, int, double> level, int w, int h, double u, double v, int f)
        {
            double s = u * w - 0.5, t = (1 - v) * h - 0.5;
            int x0 = (int)Math.Floor(s), y0 = (int)Math.Floor(t);
            double fx = s - x0, fy = t - y0;
            int Wrap(int i, int n) => ((i % n) + n) % n;
            int xa = Wrap(x0, w), xb = Wrap(x0 + 1, w), ya = Wrap(y0, h), yb = Wrap(y0 + 1, h);
            return (1 - fx) * (1 - fy) * level(xa, ya, f) + fx * (1 - fy) * level(xb, ya, f)
                + (1 - fx) * fy * level(xa, yb, f) + fx * fy * level(xb, yb, f);
        }
        var dst = new float[stride];
        double worst = 0;
        for (int i = 0; i < 4 * W; i++)
            for (int k = 0; k < 4 * H; k++)
            {
                float u = (i + 0.37f) / (4 * W), v = (k + 0.61f) / (4 * H);
                texture.Filter(new Vector2(u, v), 1e-6f, dst);   // a footprint below a texel: level 0
                for (int f = 0; f < grid.Count; f++) worst = Math.Max(worst, Math.Abs(dst[f] - Bilinear(Level0, W, H, u, v, f)));
                texture.Filter(new Vector2(u, v), 2f / W, dst);   // two level-0 texels wide: level 1 alone
                for (int f = 0; f < grid.Count; f++) worst = Math.Max(worst, Math.Abs(dst[f] - Bilinear(Level1, W / 2, H / 2, u, v, f)));
            }
        Assert.True(worst < 2e-6, $"largest difference {worst}");
    }

    [Fact]
    public void A_whitted_render_with_small_tiles_chunks_and_blocks_equals_the_render_of_the_default_layout()
    {
        var dir = Reference.TempDir();
        var scene = LoadScene(dir, lights: 2, specular: true);
        var plain = Integrators.Render(scene, 2);
        RenderResult small;
        TexelLevels.Layout.Value = (2, 1000);   // tiles of 2 × 2 texels, a few to a chunk
        SpectralTexture.BlockOverride.Value = 1;   // one row at a time
        try { small = Integrators.Render(LoadScene(dir, lights: 2, specular: true), 2); }
        finally { TexelLevels.Layout.Value = null; SpectralTexture.BlockOverride.Value = null; }
        Assert.Equal(plain.Image.Data, small.Image.Data);
        Assert.Equal(plain.Xyz, small.Xyz);
    }

    [Theory]
    [InlineData("bsq", 4, 0)]
    [InlineData("bil", 4, 1)]
    [InlineData("bip", 5, 0)]
    [InlineData("bsq", 5, 1)]
    [InlineData("bip", 4, 1)]
    [InlineData("bil", 5, 0)]
    public void An_ENVI_cube_read_a_block_of_rows_at_a_time_gives_the_samples_written(string interleave, int type, int order)
    {
        int w = 7, h = 11, n = 5, size = type == 4 ? 4 : 8, offset = 13;
        double Value(int x, int y, int b) => x + 100 * y + 0.25 * b + 1e-3;
        var bytes = new byte[offset + w * h * n * size];
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                for (int b = 0; b < n; b++)
                {
                    int i = interleave switch { "bsq" => (b * h + y) * w + x, "bil" => (y * n + b) * w + x, _ => (y * w + x) * n + b };
                    var s = bytes.AsSpan(offset + i * size, size);
                    if (type == 4 && order == 0) BinaryPrimitives.WriteSingleLittleEndian(s, (float)Value(x, y, b));
                    else if (type == 4) BinaryPrimitives.WriteSingleBigEndian(s, (float)Value(x, y, b));
                    else if (order == 0) BinaryPrimitives.WriteDoubleLittleEndian(s, Value(x, y, b));
                    else BinaryPrimitives.WriteDoubleBigEndian(s, Value(x, y, b));
                }
        var dir = Reference.TempDir();
        var image = Path.Combine(dir, "cube.img");
        File.WriteAllBytes(image, bytes);
        File.WriteAllText(Path.Combine(dir, "cube.hdr"), string.Create(CultureInfo.InvariantCulture,
            $"ENVI\nsamples = {w}\nlines = {h}\nbands = {n}\nheader offset = {offset}\ndata type = {type}\ninterleave = {interleave}\n" +
            $"byte order = {order}\nwavelength = {{400, 410, 420, 430, 440}}\n"));
        var cube = EnviReader.Open(image);
        var block = new float[3 * w * n];
        for (int y0 = 0; y0 < h; y0 += 3)
        {
            int rows = Math.Min(3, h - y0);
            cube.ReadRows(y0, rows, block);
            for (int r = 0; r < rows; r++)
                for (int x = 0; x < w; x++)
                    for (int b = 0; b < n; b++) Assert.Equal((float)Value(x, y0 + r, b), block[(r * w + x) * n + b]);
        }
        // The whole-cube reader gives the same.
        var whole = EnviReader.Read(image);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                for (int b = 0; b < n; b++) Assert.Equal((float)Value(x, y, b), whole[x, y, b]);
    }

    [Fact]
    public void A_truncated_ENVI_texture_is_bad_input_before_a_sample_is_read()
    {
        var dir = Reference.TempDir();
        SpectralTextureTests.WriteEnvi(Path.Combine(dir, "t.img"), 4, 4, [400, 500, 600], new float[4 * 4 * 3]);
        var bytes = File.ReadAllBytes(Path.Combine(dir, "t.img"));
        File.WriteAllBytes(Path.Combine(dir, "t.img"), bytes[..^4]);
        var e = Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() => EnviReader.Open(Path.Combine(dir, "t.img")));
        Assert.Contains("holds only", e.Message);
    }
}
