using System.Globalization;
using System.Numerics;
using System.Text;
using SpectralRenderer.Geometry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;
using SpectralRenderer.Tests.Rendering;

namespace SpectralRenderer.Tests.Media;

/// <summary>
/// Heterogeneous media from a density grid (Scenes/GridMedium.cs, Scenes/DensityGrid.cs, Scenes/Loading/DensityGridReader.cs):
/// the readers against bytes laid out here by hand (Mitsuba's .vol header and NumPy's .npy header), the exact optical depth
/// against the closed-form integral of a linear density, Beer–Lambert through a grid in both integrators against
/// exp(−σ_a·τ) per band, and the path tracer's null-collision tracking against the furnace and the homogeneous medium.
/// </summary>
public class GridMediumTests(Xunit.Abstractions.ITestOutputHelper output)
{
    /// <summary>Mitsuba's .vol (volumegrid.cpp): "VOL", 3, int32 1, int32 nx ny nz, int32 1 channel, 6 float32 bbox, the data.</summary>
    internal static byte[] Vol(int nx, int ny, int nz, Vector3 min, Vector3 max, Func<int, int, int, float> density)
    {
        var stream = new MemoryStream();
        using (var w = new BinaryWriter(stream))
        {
            w.Write("VOL"u8); w.Write((byte)3); w.Write(1); w.Write(nx); w.Write(ny); w.Write(nz); w.Write(1);
            foreach (float v in new[] { min.X, min.Y, min.Z, max.X, max.Y, max.Z }) w.Write(v);
            for (int z = 0; z < nz; z++) for (int y = 0; y < ny; y++) for (int x = 0; x < nx; x++) w.Write(density(x, y, z));
        }
        return stream.ToArray();
    }

    /// <summary>A .npy version 1.0 of float64 in C order with shape (nz, ny, nx): its header dict padded to 64 bytes.</summary>
    internal static byte[] Npy(int nx, int ny, int nz, Func<int, int, int, double> density)
    {
        var dict = $"{{'descr': '<f8', 'fortran_order': False, 'shape': ({nz}, {ny}, {nx}), }}";
        int total = 10 + dict.Length + 1;
        dict = dict.PadRight(dict.Length + (64 - total % 64) % 64) + "\n";
        var stream = new MemoryStream();
        using (var w = new BinaryWriter(stream))
        {
            w.Write(new byte[] { 0x93, (byte)'N', (byte)'U', (byte)'M', (byte)'P', (byte)'Y', 1, 0 });
            w.Write((ushort)dict.Length); w.Write(Encoding.ASCII.GetBytes(dict));
            for (int z = 0; z < nz; z++) for (int y = 0; y < ny; y++) for (int x = 0; x < nx; x++) w.Write(density(x, y, z));
        }
        return stream.ToArray();
    }

    static float Distinct(int x, int y, int z) => 100 * z + 10 * y + x;

    /// <summary>The centre of cell (x, y, z) of an n-cell grid over [min, max].</summary>
    static Vector3 Centre(DensityGrid g, int x, int y, int z) =>
        g.Min + (new Vector3(x, y, z) + new Vector3(0.5f)) * (g.Max - g.Min) / new Vector3(g.Nx, g.Ny, g.Nz);

    [Fact]
    public void A_vol_file_laid_out_here_reads_back_x_fastest_with_its_bounding_box()
    {
        var min = new Vector3(-1, 0, 2);
        var max = new Vector3(3, 1, 2.5f);
        var s = DensityGridReader.Read(Vol(4, 3, 2, min, max, Distinct), "t.vol");
        Assert.Equal((4, 3, 2), (s.Nx, s.Ny, s.Nz));
        Assert.Equal((min, max), s.Bounds!.Value);
        var grid = new DensityGrid(s.Data, s.Nx, s.Ny, s.Nz, min, max);
        for (int z = 0; z < 2; z++) for (int y = 0; y < 3; y++) for (int x = 0; x < 4; x++)
            Assert.Equal(Distinct(x, y, z), grid.Density(Centre(grid, x, y, z)), 3);
        Assert.Equal(0, grid.Density(new Vector3(3.01f, 0.5f, 2.2f)));   // outside the box
        Assert.Equal(123, grid.Maximum);
    }

    [Fact]
    public void A_npy_array_laid_out_here_is_indexed_z_y_x()
    {
        var s = DensityGridReader.Read(Npy(4, 3, 2, (x, y, z) => Distinct(x, y, z)), "t.npy");
        Assert.Equal((4, 3, 2), (s.Nx, s.Ny, s.Nz));
        Assert.Null(s.Bounds);
        var grid = new DensityGrid(s.Data, s.Nx, s.Ny, s.Nz, Vector3.Zero, Vector3.One);
        for (int z = 0; z < 2; z++) for (int y = 0; y < 3; y++) for (int x = 0; x < 4; x++)
            Assert.Equal(Distinct(x, y, z), grid.Density(Centre(grid, x, y, z)), 3);
        // halfway between two samples along x, trilinear: their mean
        var half = (Centre(grid, 1, 2, 1) + Centre(grid, 2, 2, 1)) / 2;
        Assert.Equal((Distinct(1, 2, 1) + Distinct(2, 2, 1)) / 2, grid.Density(half), 3);
    }

    // d = A + Bx·x + By·y + Bz·z at the cell centres: trilinear reproduces it between the outermost centres, and holds each
    // coordinate at the outermost centre beyond them, so d(p) = A + Σ_a B_a·clamp(p_a, first centre, last centre).
    const double A = 0.3, Bx = 0.5, By = -0.2, Bz = 0.8;
    static readonly Vector3 Lo = new(-1, -0.5f, 0), Hi = new(1, 1.5f, 3);
    static readonly int[] Cells = [5, 4, 6];

    static DensityGrid LinearGrid()
    {
        var data = new float[Cells[0] * Cells[1] * Cells[2]];
        var size = Hi - Lo;
        for (int z = 0; z < Cells[2]; z++) for (int y = 0; y < Cells[1]; y++) for (int x = 0; x < Cells[0]; x++)
        {
            double px = Lo.X + (x + 0.5) * size.X / Cells[0], py = Lo.Y + (y + 0.5) * size.Y / Cells[1];
            double pz = Lo.Z + (z + 0.5) * size.Z / Cells[2];
            data[(z * Cells[1] + y) * Cells[0] + x] = (float)(A + Bx * px + By * py + Bz * pz);
        }
        return new DensityGrid(data, Cells[0], Cells[1], Cells[2], Lo, Hi);
    }

    /// <summary>∫ of the linear density along o + sω over s in [0, t] ∩ the box, in closed form piece by piece.</summary>
    static double LinearOpticalDepth(Vector3 o, Vector3 w, double t)
    {
        double near = 0, far = t;
        for (int a = 0; a < 3; a++)
        {
            if (w[a] == 0) { if (o[a] < Lo[a] || o[a] > Hi[a]) return 0; continue; }
            double t0 = (Lo[a] - o[a]) / w[a], t1 = (Hi[a] - o[a]) / w[a];
            near = Math.Max(near, Math.Min(t0, t1)); far = Math.Min(far, Math.Max(t0, t1));
        }
        if (!(near < far)) return 0;
        double tau = A * (far - near);
        double[] b = [Bx, By, Bz];
        for (int a = 0; a < 3; a++)
        {
            double cell = (Hi[a] - Lo[a]) / Cells[a], first = Lo[a] + cell / 2, last = Hi[a] - cell / 2;
            // ∫ clamp(o + ω s, first, last) ds: straight or constant between the two clamp points, so each piece is its
            // length times its midpoint's value.
            var cuts = new List<double> { near, far };
            if (w[a] != 0)
                foreach (double c in new[] { (first - o[a]) / w[a], (last - o[a]) / w[a] }) if (c > near && c < far) cuts.Add(c);
            cuts.Sort();
            for (int i = 0; i + 1 < cuts.Count; i++)
            {
                double mid = o[a] + w[a] * (cuts[i] + cuts[i + 1]) / 2;
                tau += b[a] * (cuts[i + 1] - cuts[i]) * Math.Clamp(mid, first, last);
            }
        }
        return tau;
    }

    [Theory]
    [InlineData(-3, 0.2, 1.1, 1, 0.1, 0.3, 100)]   // crosses the whole box obliquely
    [InlineData(0.1, 0.7, 1.4, 0.2, -0.3, 1, 1.1)]   // starts inside, stops inside
    [InlineData(0.3, 0.2, -2, 0, 0, 1, float.PositiveInfinity)]   // along z through every layer, to infinity
    [InlineData(0.95, 1.45, 2.9, -1, -1, -1, 2)]   // from a corner cell's clamped margin, back through the diagonal
    [InlineData(-3, 3, 1, 1, 0, 0, 10)]   // misses the box
    public void The_optical_depth_through_a_linear_density_is_its_closed_form_integral(
        float ox, float oy, float oz, float wx, float wy, float wz, float t)
    {
        var o = new Vector3(ox, oy, oz);
        var w = Vector3.Normalize(new Vector3(wx, wy, wz));
        double seen = LinearGrid().OpticalDepth(o, w, t), expected = LinearOpticalDepth(o, w, t);
        output.WriteLine($"τ = {seen:g9} vs {expected:g9}");
        Assert.True(Math.Abs(seen - expected) <= 1e-5 * Math.Max(expected, 1e-3), $"{seen} vs {expected}");
    }

    const double Le = 2;

    /// <summary>
    /// A uniform sky of radiance L_e seen straight through a null-bounded box (index-matched, size 2 × 2 × 1 about the
    /// origin) filled with an absorbing grid medium placed in the box's bounds: a .npy whose density rises along z,
    /// d = 0.5 + 1.5·k/7 in layer k of 8 (so τ along z is the closed form of that clamped ramp), σ_a(λ) from 0.2 at 380 nm
    /// to 2 at 780 nm per unit — linear, so a band's mean is its centre's value. L = L_e·exp(−σ̄_a,b·τ) per band to 1e-4.
    /// </summary>
    [Theory]
    [InlineData("whitted")]
    [InlineData("path")]
    public void A_sky_seen_through_an_absorbing_density_ramp_is_L_e_exp_minus_sigma_a_tau_in_every_band(string integrator)
    {
        var dir = Reference.TempDir();
        var npy = Path.Combine(dir, "ramp.npy");
        File.WriteAllBytes(npy, Npy(2, 3, 8, (x, y, z) => 0.5 + 1.5 * z / 7.0));
        var scene = SceneText.Load($$"""
            { "radiometry": "physical", "bands": "380:780:80", "max_depth": 8,
              "integrator": { "type": "path", "spectral_grid": 5, "rr_depth": 1000, "sampler": "independent" },
              "background": "constant:{{Le}}",
              "camera": { "position": [0, 0, -3], "look_at": [0, 0, 0] },
              "materials": { "boundary": { "transmit": 1, "ior": 1 } },
              "objects": [ { "type": "box", "center": [0, 0, 0], "size": [2, 2, 1], "material": "boundary",
                             "medium": { "type": "grid", "file": "{{npy}}", "sigma_a": [[380, 0.2], [780, 2]] } } ] }
            """);
        var (seen, _) = PathIntegratorTests.Estimate(scene, new Ray(new Vector3(0.1f, 0.05f, -3), Vector3.UnitZ), 4, integrator);
        // Along z over [−0.5, 0.5]: cells of 1/8, layer centres from −0.4375 to 0.4375, the ramp held beyond them:
        // τ = 0.0625·0.5 + ∫ over the centres (mean 1.25 over 0.875) + 0.0625·2.
        double tau = 0.0625 * 0.5 + 0.875 * 1.25 + 0.0625 * 2;
        for (int b = 0; b < 80; b++)
        {
            double sigma = 0.2 + 1.8 * (382.5 + 5 * b - 380) / 400, expected = Le * Math.Exp(-sigma * tau);
            Assert.True(Math.Abs(seen[b] - expected) <= 1e-4 * expected, $"band {b}: {seen[b]} vs {expected}");
        }
        output.WriteLine($"{integrator}: τ = {tau}, first band {seen[0]:g6}, last {seen[79]:g6}");
    }

    const string Bands = "\"bands\": \"400:700:3\"";
    const string Integrator = "\"integrator\": { \"type\": \"path\", \"spectral_grid\": 100, \"rr_depth\": 1000, "
        + "\"sampler\": \"independent\", \"max_depth\": -1 }";

    /// <summary>An emitting black sphere of radius 1 about the camera in the scene's <paramref name="medium"/>.</summary>
    static Scene Furnace(string medium) => SceneText.Load($$"""
        { "radiometry": "physical", {{Bands}}, {{Integrator}}, "medium": {{medium}},
          "camera": { "position": [0, 0, 0], "look_at": [0, 0, 1] },
          "materials": { "wall": { "type": "lambertian", "reflectance": 0,
                                   "emission": { "spectrum": [[380, 1], [780, 1]], "radiance": {{Le}}, "two_sided": true } } },
          "objects": [ { "type": "sphere", "radius": 1, "material": "wall" } ] }
        """);

    static readonly Ray Out = new(Vector3.Zero, Vector3.Normalize(new Vector3(0.3f, 0.1f, 1)));

    /// <summary>A .vol over [−1.2, 1.2]³ with the given densities; its path.</summary>
    static string VolFile(int n, Func<int, int, int, float> density)
    {
        var path = Path.Combine(Reference.TempDir(), "grid.vol");
        File.WriteAllBytes(path, Vol(n, n, n, new Vector3(-1.2f), new Vector3(1.2f), density));
        return path;
    }

    /// <summary>
    /// Albedo 1 inside an emitting boundary is a furnace whatever the density: L = L_e in every band. The density is a
    /// 5³ grid of values in [0.1, 2.5] drawn from a fixed seed and σ_t = 1, 2, 3 per unit in the three bands, so the
    /// tracking meets null collisions of every size (σ_n = σ̄ − d(x)·σ_t from 0 to almost σ̄).
    /// </summary>
    [Fact]
    public void A_white_heterogeneous_medium_inside_an_emitting_boundary_is_a_furnace_L_e_in_every_band()
    {
        var random = new Random(41);
        var values = Enumerable.Range(0, 125).Select(_ => (float)(0.1 + 2.4 * random.NextDouble())).ToArray();
        var vol = VolFile(5, (x, y, z) => values[(z * 5 + y) * 5 + x]);
        var medium = $$"""
            { "type": "grid", "file": "{{vol}}", "albedo": 1, "sigma_t": [[400, 0.5], [700, 3.5]], "phase": { "type": "hg", "g": 0.5 } }
            """;
        var (seen, error) = PathIntegratorTests.Estimate(Furnace(medium), Out, 10000);
        for (int b = 0; b < 3; b++)
        {
            output.WriteLine($"band {b}: {seen[b]:g6} ± {error[b]:g3} vs L_e = {Le}");
            Assert.True(error[b] > 0 && Math.Abs(seen[b] - Le) <= 3 * error[b], $"band {b}: {seen[b]} ± {error[b]}");
        }
    }

    /// <summary>
    /// A grid of constant density ½ with twice the coefficients is the homogeneous medium (a second method: the homogeneous
    /// tracking with its exact Beer–Lambert), inside the emitting sphere with a chromatic albedo &lt; 1 where the answer
    /// depends on the medium: the two means agree within 3σ of their difference, per band.
    /// </summary>
    [Fact]
    public void A_constant_density_grid_equals_the_homogeneous_medium_within_noise()
    {
        var vol = VolFile(3, (_, _, _) => 0.5f);
        const string Albedo = "[[400, 0.3], [700, 0.9]]";
        var grid = $$"""{ "type": "grid", "file": "{{vol}}", "albedo": {{Albedo}}, "sigma_t": [[400, 1], [700, 7]] }""";
        var homogeneous = $$"""{ "albedo": {{Albedo}}, "sigma_t": [[400, 0.5], [700, 3.5]] }""";
        var (a, ea) = PathIntegratorTests.Estimate(Furnace(grid), Out, 20000);
        var (h, eh) = PathIntegratorTests.Estimate(Furnace(homogeneous), Out, 20000);
        for (int b = 0; b < 3; b++)
        {
            double sigma = Math.Sqrt(ea[b] * ea[b] + eh[b] * eh[b]);
            output.WriteLine($"band {b}: grid {a[b]:g6} ± {ea[b]:g3}, homogeneous {h[b]:g6} ± {eh[b]:g3}");
            Assert.True(Math.Abs(a[b] - h[b]) <= 3 * sigma && h[b] < 0.95 * Le, $"band {b}: {a[b]} vs {h[b]} (σ {sigma})");
        }
    }
}
