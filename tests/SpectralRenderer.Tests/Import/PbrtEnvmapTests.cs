using System.Buffers.Binary;
using System.Globalization;
using System.Numerics;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Import;
using SpectralRenderer.Scenes.Import.Pbrt;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Import;

/// <summary>
/// pbrt-v4's image infinite light (an equal-area octahedral square, Scenes/EqualAreaSquare.cs) imported as our envmap sky
/// with "mapping": "equal-area": the mapping's fixed points and its equal areas against spherical excess (solid angles of
/// the images of square cells computed by Van Oosterom–Strackee), and renders of a ρ = 0.5 board against pbrt's definition
/// of its units — a pixel of value c at scale s has luminance ∫ȳ·L dλ = s·c (683·s·c cd/m²) — so a constant map lights an
/// upward board with E = π·L, a patch of pixels from the direction the diamond geometry puts it in with L·Ω (Ω = 4π/N² per
/// pixel), and "illuminance" as pbrt-v4's lights.cpp normalises it.
/// </summary>
public sealed class PbrtEnvmapTests : IDisposable
{
    readonly string _dir = Directory.CreateTempSubdirectory("pbrt-envmap-").FullName;

    public void Dispose() => Directory.Delete(_dir, true);

    static void Near(Vector3 expected, Vector3 actual) => Assert.True(Vector3.Distance(expected, actual) < 1e-6f, $"{actual}");

    [Fact]
    public void The_square_centre_is_plus_z_its_corners_minus_z_and_the_diamond_the_equator()
    {
        float h = MathF.Sqrt(0.5f);
        Near(Vector3.UnitZ, EqualAreaSquare.ToSphere(0.5, 0.5));
        Near(-Vector3.UnitZ, EqualAreaSquare.ToSphere(0, 0));
        Near(-Vector3.UnitZ, EqualAreaSquare.ToSphere(1, 1));
        Near(Vector3.UnitX, EqualAreaSquare.ToSphere(1, 0.5));     // the diamond's corners: ±x, ±y
        Near(Vector3.UnitY, EqualAreaSquare.ToSphere(0.5, 1));
        Near(-Vector3.UnitX, EqualAreaSquare.ToSphere(0, 0.5));
        Near(new Vector3(h, h, 0), EqualAreaSquare.ToSphere(0.75, 0.75));   // the middle of the diamond's edge
        Near(new Vector3(-h, h, 0), EqualAreaSquare.ToSphere(0.25, 0.75));
        var rng = new Random(7);
        for (int i = 0; i < 1000; i++)
        {
            double u = rng.NextDouble(), v = rng.NextDouble();
            var d = EqualAreaSquare.ToSphere(u, v);
            Assert.Equal(1, d.Length(), 1e-6);
            var back = EqualAreaSquare.ToSquare(d);
            Assert.True(Math.Abs(back.X - u) < 2e-6 && Math.Abs(back.Y - v) < 2e-6, $"({u}, {v}) → {d} → {back}");
        }
    }

    /// <summary>The solid angle of the spherical triangle a, b, c (unit vectors): Van Oosterom &amp; Strackee (1983).</summary>
    static double Triangle(Vector3 a, Vector3 b, Vector3 c)
    {
        double det = Vector3.Dot(a, Vector3.Cross(b, c));
        double div = 1 + Vector3.Dot(a, b) + Vector3.Dot(b, c) + Vector3.Dot(c, a);
        return Math.Abs(2 * Math.Atan2(det, div));
    }

    [Fact]
    public void Equal_areas_of_the_square_are_equal_solid_angles()
    {
        // Cells of a 64 × 64 grid, each split into 8 × 8 spherical quads (edges nearly geodesic): each cell subtends 4π/64².
        const int n = 64, k = 8;
        double expected = 4 * Math.PI / (n * n), total = 0, worst = 0;
        for (int cy = 0; cy < n; cy++)
            for (int cx = 0; cx < n; cx++)
            {
                double cell = 0;
                for (int j = 0; j < k; j++)
                    for (int i = 0; i < k; i++)
                    {
                        double u0 = (cx + (double)i / k) / n, u1 = (cx + (i + 1.0) / k) / n;
                        double v0 = (cy + (double)j / k) / n, v1 = (cy + (j + 1.0) / k) / n;
                        Vector3 a = EqualAreaSquare.ToSphere(u0, v0), b = EqualAreaSquare.ToSphere(u1, v0);
                        Vector3 c = EqualAreaSquare.ToSphere(u1, v1), d = EqualAreaSquare.ToSphere(u0, v1);
                        cell += Triangle(a, b, c) + Triangle(a, c, d);
                    }
                total += cell;
                worst = Math.Max(worst, Math.Abs(cell / expected - 1));
            }
        Assert.Equal(4 * Math.PI, total, 1e-3);
        Assert.True(worst < 2e-3, $"a cell off by {worst:P3}");
    }

    /// <summary>A PFM of <paramref name="n"/> × <paramref name="n"/> grey pixels (rows top to bottom).</summary>
    string Pfm(string name, int n, Func<int, int, float> pixel)
    {
        var path = Path.Combine(_dir, name);
        using var s = File.Create(path);
        s.Write(System.Text.Encoding.ASCII.GetBytes($"PF\n{n} {n}\n-1.0\n"));
        var b = new byte[4];
        for (int row = n - 1; row >= 0; row--)
            for (int x = 0; x < n; x++)
                for (int c = 0; c < 3; c++) { BinaryPrimitives.WriteSingleLittleEndian(b, pixel(x, row)); s.Write(b); }
        return path;
    }

    static string F(double v) => v.ToString("R", CultureInfo.InvariantCulture);

    /// <summary>
    /// A pbrt scene: a large ρ = 0.5 board through the origin facing <paramref name="normal"/> (pbrt's world), the camera
    /// 2 units along the normal looking at it, and <paramref name="light"/> under the transformation <paramref name="light"/>
    /// is given with; converted, rendered (absolute scaling) and the centre pixel's luminance (cd/m²) returned.
    /// </summary>
    double Board(string light, Vector3 normal, int spp = 256, bool away = false)
    {
        normal = Vector3.Normalize(normal);
        var t1 = Vector3.Normalize(Vector3.Cross(normal, MathF.Abs(normal.Y) < 0.9f ? Vector3.UnitY : Vector3.UnitX));
        var t2 = Vector3.Cross(normal, t1);
        var corners = new[] { -t1 - t2, t1 - t2, t1 + t2, -t1 + t2 }.Select(c => c * 100);
        string p = string.Join(" ", corners.Select(c => $"{F(c.X)} {F(c.Y)} {F(c.Z)}"));
        var eye = normal * 2 + 0.01f * t1;
        var at = away ? eye * 2 : Vector3.Zero;
        string text = $"LookAt {F(eye.X)} {F(eye.Y)} {F(eye.Z)}  {F(at.X)} {F(at.Y)} {F(at.Z)}  {F(t2.X)} {F(t2.Y)} {F(t2.Z)}\n"
            + "Camera \"perspective\" \"float fov\" 5\nFilm \"rgb\" \"integer xresolution\" 4 \"integer yresolution\" 4\n"
            + $"Sampler \"sobol\" \"integer pixelsamples\" {spp}\nWorldBegin\n{light}\n"
            + "Material \"diffuse\" \"spectrum reflectance\" [ 300 0.5 900 0.5 ]\n"
            + $"Shape \"trianglemesh\" \"point3 P\" [ {p} ] \"integer indices\" [ 0 1 2 0 2 3 ]\n";
        var path = Path.Combine(_dir, "scene.pbrt");
        var imported = new PbrtConverter(path, new ImportOptions()).ConvertText(text);
        imported.Scene["scaling"] = "absolute";
        var scene = SceneLoader.Parse(ImportWriter.InlineJson(imported), path);
        Assert.Equal(EnvironmentMapping.EqualArea, scene.Environment!.Mapping);
        var result = PbrtLightTests.Render(scene, 2);
        double sum = 0;
        for (int y = 1; y < 3; y++) for (int x = 1; x < 3; x++) sum += result.Xyz![(y * 4 + x) * 3 + 1];
        return sum / 4;
    }

    [Fact]
    public void A_constant_map_lights_an_upward_board_with_pi_L_and_is_seen_as_L()
    {
        Pfm("grey.pfm", 16, (_, _) => 1.5f);
        const double scale = 2;
        double lv = 683 * scale * 1.5;   // pbrt: luminance s·c nits
        double sky = Board("LightSource \"infinite\" \"string filename\" \"grey.pfm\" \"float scale\" 2", Vector3.UnitZ, 1, away: true);
        Assert.True(Math.Abs(sky / lv - 1) < 1e-3, $"the sky seen: {sky} cd/m² instead of {lv}");
        // E = π·L from the whole hemisphere above the board, whatever way the map is turned; the board sends ρ·E/π = 0.5·L.
        foreach (var normal in new[] { Vector3.UnitZ, new Vector3(0.3f, -0.5f, 0.8f) })
        {
            double board = Board($"Rotate 30 1 1 0\nLightSource \"infinite\" \"string filename\" \"grey.pfm\" \"float scale\" {F(scale)}",
                normal, 256);
            Assert.True(Math.Abs(board / (0.5 * lv) - 1) < 5e-3, $"{board} cd/m² instead of {0.5 * lv}");
        }
    }

    [Fact]
    public void A_patch_of_pixels_lights_from_its_direction_with_L_times_its_solid_angle()
    {
        // 64 × 64 pixels, the 2 × 2 about (¾, ¾) bright: the middle of the diamond's edge, light-space direction (1, 1, 0)/√2,
        // Ω = 4·4π/64². "Rotate -90 1 0 0" takes the light's +z to +y: the patch is at (1, 0, −1)/√2 in pbrt's world.
        const int n = 64;
        const float c = 40;
        Pfm("patch.pfm", n, (x, y) => x is 47 or 48 && y is 47 or 48 ? c : 0);
        string light = "AttributeBegin\nRotate -90 1 0 0\nLightSource \"infinite\" \"string filename\" \"patch.pfm\"\nAttributeEnd";
        var towards = new Vector3(1, 0, -1);
        double omega = 4 * 4 * Math.PI / (n * n), lv = 683 * c;
        // The patch spans ≈ 0.09 rad: cos θ over it is ≥ 0.998, so E = L·Ω to 0.2 %; ρ/π·E seen on the board.
        double facing = Board(light, towards);
        double expected = 0.5 / Math.PI * lv * omega;
        Assert.True(Math.Abs(facing / expected - 1) < 1e-2, $"{facing} cd/m² instead of {expected}");
        // Turned 60° away from the patch: half of it (cos 60°); facing away: none.
        var tilted = Vector3.Transform(Vector3.Normalize(towards), Quaternion.CreateFromAxisAngle(Vector3.UnitY, MathF.PI / 3));
        double half = Board(light, tilted);
        Assert.True(Math.Abs(half / (0.5 * expected) - 1) < 2e-2, $"{half} cd/m² instead of {0.5 * expected}");
        Assert.Equal(0, Board(light, -towards, 16));
    }

    [Fact]
    public void Illuminance_scales_the_map_as_pbrt_v4_does()
    {
        // pbrt-v4 lights.cpp: scale·E/k_e with k_e = 2π/N² Σ lum·cos θ over the pixels above the horizon, which for a
        // constant map of luminance c tends to c·π/2 (the hemisphere's ∫cos θ dω = π, times 2π/4π): the map is scaled to
        // luminance 2E/π, and an upward board receives 2E.
        Pfm("sky.pfm", 64, (_, _) => 0.7f);
        const double e = 1000;
        double board = Board($"LightSource \"infinite\" \"string filename\" \"sky.pfm\" \"float illuminance\" {F(e)}", Vector3.UnitZ);
        double expected = 683 * 0.5 / Math.PI * 2 * e;
        Assert.True(Math.Abs(board / expected - 1) < 1e-2, $"{board} cd/m² instead of {expected}");
    }

    [Fact]
    public void A_map_that_is_not_square_or_not_hdr_is_one_line_with_a_hint()
    {
        var path = Path.Combine(_dir, "scene.pbrt");
        var wide = Path.Combine(_dir, "wide.pfm");
        File.WriteAllBytes(wide, [.. System.Text.Encoding.ASCII.GetBytes("PF\n2 1\n-1.0\n"), .. new byte[24]]);
        const string head = "Camera \"perspective\"\nWorldBegin\n";
        const string shape = "\nShape \"sphere\"\n";
        var ex = Assert.Throws<InputException>(() => new PbrtConverter(path, new ImportOptions())
            .ConvertText(head + "LightSource \"infinite\" \"string filename\" \"wide.pfm\"" + shape));
        Assert.Contains("2 × 1 pixels", ex.Message);
        Assert.Contains("makeequiarea", ex.Message);
        File.WriteAllBytes(Path.Combine(_dir, "sky.png"), [0]);
        ex = Assert.Throws<InputException>(() => new PbrtConverter(path, new ImportOptions())
            .ConvertText(head + "LightSource \"infinite\" \"string filename\" \"sky.png\"" + shape));
        Assert.Contains("--lenient", ex.Message);
        var lenient = new PbrtConverter(path, new ImportOptions(Lenient: true))
            .ConvertText(head + "LightSource \"infinite\" \"string filename\" \"sky.png\"" + shape);
        Assert.Contains(lenient.Report.Entries, x => x.Kind == "error" && x.Element.Contains("filename"));
    }
}
