using System.Globalization;
using SpectralRenderer.Imaging;
using SpectralRenderer.Output;
using SpectralRenderer.Output.Products;
using SpectralRenderer.Pipeline;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Pipeline;

/// <summary>
/// A new output format is one product plus one registration: a product defined here, in the test assembly, registered
/// in the table and asked for by name, is written by the normal job and listed in render.json's files.
/// </summary>
public class OutputProductTests
{
    /// <summary>luminance.csv: per pixel "x,y,Y" with Y = Σ_b Wy[b]·L[b] (eq. 3 with the render's weights).</summary>
    sealed class LuminanceCsvProduct : OutputProduct
    {
        public override string Name => "test-luminance-csv";

        public override IEnumerable<(string Part, long Bytes)> Memory(Scene scene, int threads) =>
            [("luminance.csv", 32L * scene.Camera.Width * scene.Camera.Height)];

        public override void Write(ProductContext c, int part, Action<string> done)
        {
            var image = c.Image;
            var wy = c.Scene.Colorimeter.Wy;
            var csv = new System.Text.StringBuilder("x,y,Y\n");
            for (int y = 0; y < image.Height; y++)
                for (int x = 0; x < image.Width; x++)
                {
                    var px = image.Pixel(x, y);
                    double sum = 0;
                    for (int b = 0; b < image.Bands; b++) sum += wy[b] * px[b];
                    csv.Append(CultureInfo.InvariantCulture, $"{x},{y},{sum:R}\n");
                }
            AtomicFile.WriteAllText(Path.Combine(c.OutDir, "luminance.csv"), csv.ToString());
            done("luminance.csv");
        }

        public override bool Owns(string file) => file == "luminance.csv";
    }

    static readonly Lazy<bool> Registered = new(() => { OutputProductTable.Register(new LuminanceCsvProduct()); return true; });

    const string Scene = """
    {
      "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 9, "height": 7 },
      "materials": { "green": { "diffuse": "colorchecker:14" } },
      "lights": [ { "type": "point", "position": [0, 3, 3], "spectrum": "D65" } ],
      "objects": [ { "type": "sphere", "radius": 1, "material": "green" } ]
    }
    """;

    [Fact]
    public void A_product_registered_from_the_test_assembly_is_written_by_the_job_and_listed_in_render_json()
    {
        Assert.True(Registered.Value);
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, Scene);
        var outDir = Path.Combine(dir, "out");
        RenderJob.Run(new RenderRequest
        {
            ScenePath = scene,
            Overrides = new SceneOverrides { Formats = "npy" },
            Products = ["test-luminance-csv"],
            Threads = 1,
            OutDir = outDir,
        });
        var manifest = RenderManifest.Read(outDir);
        Assert.Equal(["spectral.npy", "wavelengths.csv", "xyz.npy", "luminance.csv"], manifest.Files);

        // Independently: eq. 3's Y from the cube read back from spectral.npy with render.json's own weights.
        var cube = SpectralFiles.Read(outDir, manifest.Grid);
        var rows = File.ReadAllLines(Path.Combine(outDir, "luminance.csv"));
        Assert.Equal(1 + 9 * 7, rows.Length);
        foreach (var row in rows.Skip(1))
        {
            var cells = row.Split(',');
            int x = int.Parse(cells[0], CultureInfo.InvariantCulture), y = int.Parse(cells[1], CultureInfo.InvariantCulture);
            var bands = cube.Pixel(x, y).ToArray().Select(v => (double)v).ToArray();
            Assert.Equal(manifest.ToXyz(bands).Y, double.Parse(cells[2], CultureInfo.InvariantCulture), 12);
        }
        Assert.Contains(RenderMemory.Estimate(SceneLoader.Load(scene), 1, OutputProductTable.Named(["test-luminance-csv"])),
            p => p.Part == "luminance.csv");
    }

    [Fact]
    public void The_command_lines_formats_name_a_registered_product_beside_the_built_in_ones()
    {
        Assert.True(Registered.Value);
        var dir = Reference.TempDir();
        var scene = Path.Combine(dir, "scene.json");
        File.WriteAllText(scene, Scene);
        var outDir = Path.Combine(dir, "out");
        var (code, _, err) = global::SpectralRenderer.Tests.Cli.CliRunner.Run("render", scene, "-o", outDir, "--quiet", "--formats",
            "npy,test-luminance-csv");
        Assert.True(code == 0, err);
        Assert.Equal(["spectral.npy", "wavelengths.csv", "xyz.npy", "luminance.csv"], RenderManifest.Read(outDir).Files);
        Assert.Equal(1 + 9 * 7, File.ReadAllLines(Path.Combine(outDir, "luminance.csv")).Length);
    }

    [Fact]
    public void A_product_name_nobody_registered_is_bad_input()
    {
        var e = Assert.Throws<global::SpectralRenderer.Diagnostics.InputException>(() => OutputProductTable.Named(["no-such-product"]));
        Assert.Contains("no output product 'no-such-product'", e.Message);
    }

    [Fact]
    public void Every_file_of_the_built_in_products_has_one_owner()
    {
        foreach (var f in new[] { "preview.png", "bands/band-01-400-410nm.png", "bands.png", "object-id.png", "mask-lit-0.png",
            "mask-highlight.png",
            "reflectance.exr", "spectral.exr", "spectral.img", "spectral.hdr", "spectral.npy", "wavelengths.csv", "lights/lights.json",
                "grids/desk.csv" })
            Assert.Single(OutputProductTable.All, p => p.Owns(f));
    }
}
