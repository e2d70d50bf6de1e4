using System.Text;
using System.Text.Json.Nodes;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Import;
using SpectralRenderer.Scenes.Import.Gltf;
using SpectralRenderer.Scenes.Loading;
using Xunit.Abstractions;

namespace SpectralRenderer.Tests.Import;

/// <summary>
/// The glTF 2.0 reader against numbers computed here by hand or by the laws of photometry: a KHR_lights_punctual point
/// light's luminance on a white diffuser (I/d²·ρ/π), a JPEG base-colour texture's texels (their sRGB values known from how
/// the file was made), world positions through a node hierarchy (T·R·S and a column-major matrix multiplied out by hand),
/// the camera, lights, materials and the dispersion's Abbe number recomputed from the written Cauchy coefficients; the
/// same scene as .gltf and .glb; determinism; bad input as one line with the JSON path.
/// </summary>
public class GltfImportTests(ITestOutputHelper output)
{
    static ImportedScene Convert(string path, bool lenient = false) =>
        new GltfFormat().Convert(path, new ImportOptions(Lenient: lenient));

    /// <summary>The converted scene loaded as the renderer loads it (relative paths from the asset's folder), after
    /// <paramref name="edit"/> changes render settings (size, samples, scaling).</summary>
    static Scene Load(ImportedScene imported, string path, Action<JsonObject>? edit = null)
    {
        var json = (JsonObject)imported.Scene.DeepClone();
        edit?.Invoke(json);
        return SceneLoader.Parse(Encoding.UTF8.GetBytes(json.ToJsonString()), Path.Combine(Path.GetDirectoryName(path)!, "scene.json"));
    }

    static JsonObject Node(params (string Key, JsonNode Value)[] keys)
    {
        var o = new JsonObject();
        foreach (var (k, v) in keys) o[k] = v;
        return o;
    }

    static JsonArray A(params double[] v) => [.. v.Select(x => (JsonNode)x)];

    /// <summary>A camera node at z = 5 looking down −Z with the given vertical field of view (radians), aspect 1.</summary>
    static void Camera(GltfBuilder b, double yfov)
    {
        b.Add("cameras", new JsonObject
        {
            ["type"] = "perspective",
            ["perspective"] = new JsonObject { ["yfov"] = yfov, ["aspectRatio"] = 1.0, ["znear"] = 0.01 },
        });
        b.Node(Node(("camera", 0), ("translation", A(0, 0, 5))));
    }

    static JsonObject WhiteDiffuser(double rho) => new()
    {
        ["pbrMetallicRoughness"] = new JsonObject { ["baseColorFactor"] = A(rho, rho, rho, 1), ["metallicFactor"] = 0.0 },
        // specularFactor 0: glTF's BRDF is then its diffuse term alone, f = base colour/π (Appendix B).
        ["extensions"] = new JsonObject { ["KHR_materials_specular"] = new JsonObject { ["specularFactor"] = 0.0 } },
    };

    [Theory]
    [InlineData("whitted", 1000.0, 2.0, 1.0)]
    [InlineData("whitted", 250.0, 1.5, 0.6)]
    [InlineData("path", 1000.0, 2.0, 1.0)]
    public void A_point_light_of_I_cd_at_d_m_gives_a_diffuser_I_over_d2_rho_over_pi_cd_per_m2(string integrator, double candela,
        double d, double rho)
    {
        var b = new GltfBuilder();
        b.Add("materials", WhiteDiffuser(rho));
        b.Node(Node(("mesh", b.Square(4, material: 0))));
        b.Light(new JsonObject { ["type"] = "point", ["intensity"] = candela, ["color"] = A(1, 1, 1) });
        b.Node(Node(("extensions", new JsonObject { ["KHR_lights_punctual"] = new JsonObject { ["light"] = 0 } }),
            ("translation", A(0, 0, d))));
        Camera(b, 0.01);
        var path = b.WriteGltf(Path.Combine(Reference.TempDir(), "point.gltf"));
        var imported = Convert(path);
        var light = (JsonObject)((JsonArray)imported.Scene["lights"]!)[0]!;
        Assert.Equal(candela, (double)light["luminous_intensity"]!);
        Assert.Equal("absolute", (string)imported.Scene["scaling"]!);   // Y in cd/m²
        var scene = Load(imported, path, s =>
        {
            s["integrator"] = integrator == "path" ? new JsonObject { ["type"] = "path", ["spectral_grid"] = 1 } : "whitted";
            var c = (JsonObject)s["camera"]!;
            c["width"] = 1; c["height"] = 1; c["spp"] = 1;   // one ray through the pixel centre, straight down the light's axis
        });
        double luminance = Integrators.Render(scene).Xyz![1];
        double expected = candela / (d * d) * rho / Math.PI;
        double rel = Math.Abs(luminance - expected) / expected;
        output.WriteLine($"{integrator}: {candela} cd at {d} m, ρ = {rho}: {luminance:R} vs {expected:R} cd/m² ({rel:E2})");
        Assert.True(rel <= 1e-5, $"{luminance} vs {expected} cd/m² ({rel:E2} relative)");
    }

    /// <summary>tests/…/Import/quadrants.jpg: a 32 × 32 grey baseline JPEG (cjpeg -grayscale -quality 100) of four flat
    /// 16 × 16 quadrants, sRGB codes 40 (top left), 100 (top right), 160 (bottom left), 220 (bottom right). Flat blocks keep
    /// their DC exactly at quality 100, so these are the decoded texels.</summary>
    static readonly (int X, int Y, int Code)[] Quadrants = [(3, 3, 40), (12, 3, 100), (3, 12, 160), (12, 12, 220)];

    /// <summary>The quadrants texture on a white 2 m square filling a 16 × 16 view from 5 m (pixel (x, y) sees glTF uv
    /// ((x + ½)/16, (y + ½)/16)) under 100 lx head-on, with <paramref name="textureInfo"/> as its baseColorTexture: XYZ.</summary>
    static float[] QuadrantsSquare(JsonObject textureInfo)
    {
        var dir = Reference.TempDir();
        File.Copy(Repo.PathOf("tests", "SpectralRenderer.Tests", "Import", "quadrants.jpg"), Path.Combine(dir, "quadrants.jpg"));
        var b = new GltfBuilder();
        b.Add("images", new JsonObject { ["uri"] = "quadrants.jpg" });
        b.Add("textures", new JsonObject { ["source"] = 0 });
        var material = WhiteDiffuser(1);
        ((JsonObject)material["pbrMetallicRoughness"]!)["baseColorTexture"] = textureInfo;
        b.Add("materials", material);
        b.Node(Node(("mesh", b.Square(2, material: 0))));
        b.Light(new JsonObject { ["type"] = "directional", ["intensity"] = 100.0 });   // lux, shining down −Z onto the square
        b.Node(Node(("extensions", new JsonObject { ["KHR_lights_punctual"] = new JsonObject { ["light"] = 0 } })));
        Camera(b, 2 * Math.Atan(0.2));   // the 2 m square fills the view from 5 m
        var path = b.WriteGltf(Path.Combine(dir, "textured.gltf"));
        var scene = Load(Convert(path), path, s =>
        {
            var c = (JsonObject)s["camera"]!;
            c["width"] = 16; c["height"] = 16; c["spp"] = 1;
        });
        return Integrators.Render(scene).Xyz!;
    }

    [Fact]
    public void A_jpeg_base_colour_texture_renders_the_texel_expected_in_each_quadrant()
    {
        var jpeg = SpectralRenderer.Imaging.JpegReader.Read(Repo.PathOf("tests", "SpectralRenderer.Tests", "Import", "quadrants.jpg"));
        foreach (var (x, y, code) in Quadrants) Assert.Equal(code, jpeg.Samples[(2 * y + 1) * 32 + 2 * x + 1]);

        var xyz = QuadrantsSquare(new JsonObject { ["index"] = 0 });
        foreach (var (x, y, code) in Quadrants)
        {
            // IEC 61966-2-1 decoding; a grey's uplift is flat at that reflectance (solved to ΔE00 < 1e-4).
            double c = code / 255.0, rho = c <= 0.04045 ? c / 12.92 : Math.Pow((c + 0.055) / 1.055, 2.4);
            double expected = 100 * rho / Math.PI, luminance = xyz[(y * 16 + x) * 3 + 1];
            double rel = Math.Abs(luminance - expected) / expected;
            output.WriteLine($"pixel ({x}, {y}), texel {code}: {luminance:R} vs {expected:R} cd/m² ({rel:E2})");
            Assert.True(rel <= 1e-4, $"pixel ({x}, {y}): {luminance} vs {expected} cd/m² for code {code}");
        }
    }

    /// <summary>The code of the quadrants texture at glTF texture coordinates (u, v) (v down, the image's top row at v = 0),
    /// repeating.</summary>
    static int QuadrantCode(double u, double v)
    {
        u -= Math.Floor(u);
        v -= Math.Floor(v);
        return v < 0.5 ? (u < 0.5 ? 40 : 100) : (u < 0.5 ? 160 : 220);
    }

    [Theory]
    [InlineData(0.0, 0.0, 0.0, 2.0, 2.0)]           // tiled twice
    [InlineData(0.5, 0.0, 0.0, 0.5, 0.5)]           // the top right quadrant only
    [InlineData(0.0, 0.0, Math.PI / 2, 1.0, 1.0)]   // a quarter turn: its direction matters
    [InlineData(0.0, 1.0, Math.PI / 2, 0.5, 0.5)]   // the extension's example: the lower left quadrant, turned
    [InlineData(0.25, 0.5, 0.3, 1.5, -0.7)]         // all at once, a mirror in v
    public void KHR_texture_transform_puts_each_texel_where_the_extension_computes_it(double ou, double ov, double rotation,
        double su, double sv)
    {
        var xyz = QuadrantsSquare(new JsonObject
        {
            ["index"] = 0,
            ["extensions"] = new JsonObject
            {
                ["KHR_texture_transform"] = new JsonObject { ["offset"] = A(ou, ov), ["rotation"] = rotation, ["scale"] = A(su, sv) },
            },
        });
        int checkedPixels = 0;
        for (int y = 0; y < 16; y++)
            for (int x = 0; x < 16; x++)
            {
                // The extension's t' = T·R·S·t, R = [[cos, sin], [−sin, cos]] on glTF's v-down map (its example; glTF#1563).
                double u = (x + 0.5) / 16, v = (y + 0.5) / 16, c = Math.Cos(rotation), sn = Math.Sin(rotation);
                double tu = c * su * u + sn * sv * v + ou, tv = -sn * su * u + c * sv * v + ov;
                // Only pixels whose footprint (± a pixel, times the scale) stays inside one quadrant: texture filtering blends edges.
                double reach = 1.5 / 16 * Math.Max(Math.Abs(su), Math.Abs(sv));
                int code = QuadrantCode(tu, tv);
                bool inside = true;
                foreach (var (du, dv) in new[] { (reach, 0.0), (-reach, 0.0), (0.0, reach), (0.0, -reach) })
                    inside &= QuadrantCode(tu + du, tv + dv) == code;
                if (!inside) continue;
                double k = code / 255.0, rho = k <= 0.04045 ? k / 12.92 : Math.Pow((k + 0.055) / 1.055, 2.4);
                double expected = 100 * rho / Math.PI, luminance = xyz[(y * 16 + x) * 3 + 1];
                Assert.True(Math.Abs(luminance - expected) <= 2e-3 * expected,
                    $"pixel ({x}, {y}): {luminance} vs {expected} for code {code}");
                checkedPixels++;
            }
        Assert.True(checkedPixels >= 12, $"only {checkedPixels} pixels away from the quadrants' edges");
    }

    [Fact]
    public void Alpha_mask_below_the_cutoff_leaves_the_primitive_out_and_other_alpha_is_reported_as_approximated()
    {
        var b = new GltfBuilder();
        JsonObject Mat(string mode, double alpha, double? cutoff = null)
        {
            var m = WhiteDiffuser(0.5);
            ((JsonObject)m["pbrMetallicRoughness"]!)["baseColorFactor"] = A(0.5, 0.5, 0.5, alpha);
            m["alphaMode"] = mode;
            if (cutoff is { } c) m["alphaCutoff"] = c;
            return m;
        }
        // glTF 2.0 §3.9.4: MASK shows alpha ≥ cutoff (default 0.5): 0.3 < 0.5 is cut away, 0.3 ≥ 0.25 is shown.
        b.Add("materials", Mat("MASK", 0.3));
        b.Add("materials", Mat("MASK", 0.3, 0.25));
        b.Add("materials", Mat("BLEND", 0.4));
        for (int m = 0; m < 3; m++) b.Node(Node(("mesh", b.Square(2, material: m)), ("translation", A(3 * m, 0, 0))));
        Camera(b, 0.5);
        var path = b.WriteGltf(Path.Combine(Reference.TempDir(), "alpha.gltf"));
        var imported = Convert(path);
        Assert.Equal(2, imported.Scene["objects"]!.AsArray().Count);
        var e = imported.Report.Entries;
        Assert.Contains(e, x => x.Kind == "converted" && x.Where.EndsWith("$.meshes[0].primitives[0]") && x.Action.StartsWith("left out"));
        Assert.Contains(e, x => x.Kind == "approximated" && x.Where.EndsWith("$.materials[2].alphaMode") && x.Action.Contains("BLEND"));
        Assert.DoesNotContain(e, x => x.Where.EndsWith("$.materials[1].alphaMode"));   // 0.3 ≥ 0.25: shown, opaque, exactly
    }

    [Fact]
    public void Node_transforms_compose_down_the_hierarchy_as_computed_by_hand()
    {
        var b = new GltfBuilder();
        int mesh = b.Mesh([1, 0, 0, 0, 1, 0, 0, 0, 1], [0, 1, 2]);
        double s45 = Math.Sqrt(0.5);
        // Parent: T = (1, 2, 3), R = 90° about +Y (q = [0, sin 45°, 0, cos 45°]), S = 2. Child: a column-major matrix of
        // scale (3, 1, 1) and translation (0, 0, −1). A second root: the same mesh translated by (10, 0, 0).
        int parent = b.Node(Node(("translation", A(1, 2, 3)), ("rotation", A(0, s45, 0, s45)), ("scale", A(2, 2, 2))));
        b.Node(Node(("mesh", mesh), ("matrix", A(3, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1))), parent);
        b.Node(Node(("mesh", mesh), ("translation", A(10, 0, 0))));
        Camera(b, 0.5);
        var path = b.WriteGltf(Path.Combine(Reference.TempDir(), "hierarchy.gltf"));
        var scene = Load(Convert(path), path);
        // By hand: child (x, y, z) → (3x, y, z − 1); S: ×2; R_y(90°): (x, y, z) → (z, y, −x); T: + (1, 2, 3).
        //   (1, 0, 0) → (3, 0, −1) → (6, 0, −2) → (−2, 0, −6) → (−1, 2, −3)
        //   (0, 1, 0) → (0, 1, −1) → (0, 2, −2) → (−2, 2, 0)  → (−1, 4, 3)
        //   (0, 0, 1) → (0, 0, 0)  → (0, 0, 0)  → (0, 0, 0)   → (1, 2, 3)
        float[][] expected = [[-1, 2, -3], [-1, 4, 3], [1, 2, 3]];
        // The mesh is used by two nodes: one prototype, two instances, placed as computed by hand.
        var meshes = scene.Objects.Where(o => o.Mesh is not null).ToList();
        Assert.Equal(2, meshes.Count);
        Assert.All(meshes, o => Assert.NotNull(o.InstanceTransform));
        Assert.Same(meshes[0].Mesh, meshes[1].Mesh);
        var p = meshes[0].WorldMesh()!.Positions;
        for (int i = 0; i < 3; i++)
        {
            Assert.Equal(expected[i][0], p[i].X, 5);
            Assert.Equal(expected[i][1], p[i].Y, 5);
            Assert.Equal(expected[i][2], p[i].Z, 5);
        }
        var q = meshes[1].WorldMesh()!.Positions;
        Assert.Equal([new(11, 0, 0), new(10, 1, 0), new(10, 0, 1)], q.Take(3).ToArray());
    }

    [Fact]
    public void The_camera_node_gives_position_direction_and_vertical_fov()
    {
        var b = new GltfBuilder();
        b.Node(Node(("mesh", b.Square(1))));
        b.Add("cameras", new JsonObject
        {
            ["type"] = "perspective",
            ["perspective"] = new JsonObject { ["yfov"] = 0.6, ["aspectRatio"] = 1.5, ["znear"] = 0.1 },
        });
        // 90° about +Y: the camera's −Z looks down the scene's −X.
        double s45 = Math.Sqrt(0.5);
        b.Node(Node(("camera", 0), ("translation", A(4, 1, 0)), ("rotation", A(0, s45, 0, s45))));
        var path = b.WriteGltf(Path.Combine(Reference.TempDir(), "camera.gltf"));
        var camera = (JsonObject)Convert(path).Scene["camera"]!;
        Assert.Equal(0.6 * 180 / Math.PI, (double)camera["fov"]!, 6);
        Assert.Equal((720, 480), ((int)camera["width"]!, (int)camera["height"]!));
        Assert.Equal([4, 1, 0], ((JsonArray)camera["position"]!).Select(v => (double)v!).ToArray());
        var lookAt = ((JsonArray)camera["look_at"]!).Select(v => (double)v!).ToArray();
        Assert.Equal(3, lookAt[0], 6);
        Assert.Equal(1, lookAt[1], 6);
        Assert.Equal(0, lookAt[2], 6);
    }

    [Fact]
    public void Spot_directional_emission_metal_and_dispersion_convert_as_documented()
    {
        var b = new GltfBuilder();
        b.Add("materials", new JsonObject
        {
            ["pbrMetallicRoughness"] = new JsonObject { ["baseColorFactor"] = A(0.9, 0.9, 0.9, 1), ["roughnessFactor"] = 0.5 },
        });
        b.Add("materials", new JsonObject
        {
            ["pbrMetallicRoughness"] = new JsonObject { ["metallicFactor"] = 0.0, ["roughnessFactor"] = 0.0 },
            ["extensions"] = new JsonObject
            {
                ["KHR_materials_transmission"] = new JsonObject { ["transmissionFactor"] = 1.0 },
                ["KHR_materials_ior"] = new JsonObject { ["ior"] = 1.5168 },
                ["KHR_materials_dispersion"] = new JsonObject { ["dispersion"] = 20 / 64.17 },
                ["KHR_materials_volume"] = new JsonObject { ["thicknessFactor"] = 1.0 },
            },
        });
        b.Add("materials", new JsonObject
        {
            ["pbrMetallicRoughness"] = new JsonObject { ["metallicFactor"] = 0.0, ["baseColorFactor"] = A(0, 0, 0, 1) },
            ["emissiveFactor"] = A(1, 1, 1),
            ["extensions"] = new JsonObject { ["KHR_materials_emissive_strength"] = new JsonObject { ["emissiveStrength"] = 500.0 } },
        });
        for (int m = 0; m < 3; m++) b.Node(Node(("mesh", b.Square(1, material: m)), ("translation", A(2 * m, 0, 0))));
        b.Light(new JsonObject
        {
            ["type"] = "spot",
            ["intensity"] = 300.0,
            ["color"] = A(1, 0.5, 0.25),
            ["spot"] = new JsonObject { ["innerConeAngle"] = 0.2, ["outerConeAngle"] = 0.6 },
        });
        b.Light(new JsonObject { ["type"] = "directional", ["intensity"] = 2000.0 });
        b.Node(
            Node(("extensions", new JsonObject { ["KHR_lights_punctual"] = new JsonObject { ["light"] = 0 } }), ("translation", A(0, 3, 0)),
            ("rotation", A(-Math.Sqrt(0.5), 0, 0, Math.Sqrt(0.5)))));   // −90° about X: −Z turns to −Y, straight down
        b.Node(Node(("extensions", new JsonObject { ["KHR_lights_punctual"] = new JsonObject { ["light"] = 1 } })));
        Camera(b, 0.8);
        var path = b.WriteGltf(Path.Combine(Reference.TempDir(), "kinds.gltf"));
        var imported = Convert(path);
        var materials = (JsonObject)imported.Scene["materials"]!;

        // Metal: F0 = 0.9 at normal incidence, ((n − 1)/(n + 1))² with k = 0; GGX α = roughness² = 0.25.
        var metal = (JsonObject)materials["material0"]!;
        Assert.Equal("conductor", (string)metal["type"]!);
        double n = (double)metal["conductor"]!["n"]!;
        Assert.Equal(0.9, Math.Pow((n - 1) / (n + 1), 2), 6);
        Assert.Equal(0.25, (double)metal["roughness"]!, 9);

        // Glass: Cauchy A + B/λ² with n_d = 1.5168 at 587.56 nm and (n_d − 1)/(n_F − n_C) = 64.17 (N-BK7's Abbe number).
        var cauchy = (JsonArray)materials["material1"]!["ior"]!["cauchy"]!;
        double a = (double)cauchy[0]!, bb = (double)cauchy[1]!;
        double N(double l) => a + bb / (l * l);
        Assert.Equal(1.5168, N(587.56), 6);
        Assert.Equal(64.17, (N(587.56) - 1) / (N(486.13) - N(656.27)), 4);

        // Emission: emissive (1, 1, 1) × 500 is 500 cd/m² (glTF §3.9.3), spectrum D65.
        var emission = (JsonObject)materials["material2"]!["emission"]!;
        Assert.Equal(500.0, (double)emission["luminance"]!);
        Assert.Equal("D65", (string)emission["spectrum"]!);

        // Spot: 300 cd × Y(1, 0.5, 0.25) = 300 × (0.2126 + 0.7152/2 + 0.0722/4); the hard cone of equal flux; pointing down.
        var lights = (JsonArray)imported.Scene["lights"]!;
        var spot = (JsonObject)lights[0]!;
        Assert.Equal(300 * (0.2126 + 0.3576 + 0.01805), (double)spot["luminous_intensity"]!, 6);
        double ci = Math.Cos(0.2), co = Math.Cos(0.6);
        Assert.Equal(Math.Acos(ci - (ci - co) / 3) * 180 / Math.PI, (double)spot["cutoff"]!, 5);
        var dir = ((JsonArray)spot["direction"]!).Select(v => (double)v!).ToArray();
        Assert.Equal(-1, dir[1], 6);
        var directional = (JsonObject)lights[1]!;
        Assert.Equal(2000.0, (double)directional["illuminance"]!);
        Assert.Equal([0, 0, -1], ((JsonArray)directional["direction"]!).Select(v => (double)v!).ToArray());

        // It loads: every key is one our scene format takes.
        var scene = Load(imported, path);
        Assert.Equal(2, scene.Lights.Count);
        Assert.Contains(imported.Report.Entries, e => e.Kind == "approximated" && e.Element == "spot cone");
    }

    [Fact]
    public void The_same_scene_as_gltf_with_a_bin_file_and_as_glb_converts_to_the_same_json_and_again_to_the_same_bytes()
    {
        var b = new GltfBuilder();
        b.Add("materials", WhiteDiffuser(0.5));
        b.Node(Node(("mesh", b.Square(2, material: 0)), ("rotation", A(0, 0, Math.Sin(0.3), Math.Cos(0.3)))));
        b.Light(new JsonObject { ["type"] = "point", ["intensity"] = 50.0 });
        b.Node(Node(("extensions", new JsonObject { ["KHR_lights_punctual"] = new JsonObject { ["light"] = 0 } }),
            ("translation", A(0, 1, 2))));
        Camera(b, 0.7);
        var dir = Reference.TempDir();
        var gltf = b.WriteGltf(Path.Combine(dir, "same.gltf"), binFile: true);
        var glb = b.WriteGlb(Path.Combine(dir, "same.glb"));
        static string Text(ImportedScene s)
        {
            var json = (JsonObject)s.Scene.DeepClone();
            json.Remove("name");          // the file's name, same.gltf or same.glb
            json.Remove("description");   // which names it too
            return Encoding.UTF8.GetString(ImportWriter.InlineJson(s with { Scene = json }));
        }
        Assert.Equal(Text(Convert(gltf)), Text(Convert(glb)));
        Assert.Equal(ImportWriter.InlineJson(Convert(glb)), ImportWriter.InlineJson(Convert(glb)));
        Assert.True(new GltfFormat().Claims("x.GLB", []) && new GltfFormat().Claims("model.bin", "glTF\u0002"u8));
        // The imported scene renders the same bits on one thread and on four.
        var scene = Load(Convert(glb), glb, s => { var c = (JsonObject)s["camera"]!; c["width"] = 24; c["height"] = 16; c["spp"] = 4; });
        var one = Integrators.Render(scene, 1).Image.Data;
        var four = Integrators.Render(scene, 4).Image.Data;
        Assert.True(one.AsSpan().SequenceEqual(four), "the render differs between 1 and 4 threads");
    }

    public static TheoryData<string, string, string> BadFiles => new()
    {
        { """{ "asset": { "version": "1.0" }, "scenes": [] }""", "$.asset.version", "glTF version" },
        { """{ "asset": { "version": "2.0" }, "scenes": [ { "nodes": [ 0 ] } ], "nodes": [ { "mesh": 3 } ] }""",
            "$.nodes[0].mesh", "is not an index into \"meshes\"" },
        { """{ "asset": { "version": "2.0" }, "scenes": [ { "nodes": [ 0 ] } ], "nodes": [ { "children": [ 0 ] } ] }""",
            "$.nodes[0].children[0]", "appears twice in the hierarchy" },
        { """{ "asset": { "version": "2.0" }, "extensionsRequired": [ "KHR_draco_mesh_compression" ], "scenes": [ {} ] }""",
            "$.extensionsRequired[0]", "requires the extension KHR_draco_mesh_compression" },
        {
            """
            { "asset": { "version": "2.0" }, "scenes": [ { "nodes": [ 0 ] } ], "nodes": [ { "mesh": 0 } ],
              "meshes": [ { "primitives": [ { "attributes": { "POSITION": 0 } } ] } ],
              "accessors": [ { "componentType": 5126, "type": "VEC3", "count": 3, "bufferView": 0 } ],
              "bufferViews": [ { "buffer": 0, "byteLength": 36 } ],
              "buffers": [ { "byteLength": 36, "uri": "data:application/octet-stream;base64,AAAA" } ] }
            """,
            "$.buffers[0].byteLength", "holds 3 bytes, fewer than its byteLength 36"
        },
    };

    [Theory]
    [MemberData(nameof(BadFiles))]
    public void Bad_input_is_one_line_naming_the_file_and_the_json_path(string json, string place, string what)
    {
        var path = Path.Combine(Reference.TempDir(), "bad.gltf");
        File.WriteAllText(path, json);
        var e = Assert.Throws<InputException>(() => Convert(path));
        output.WriteLine(e.Message);
        Assert.StartsWith($"{path}: {place}", e.Message);
        Assert.Contains(what, e.Message);
        Assert.Contains("(hint: ", e.Message);
        Assert.DoesNotContain('\n', e.Message);
    }
}
