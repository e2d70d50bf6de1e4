using System.Globalization;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral colors`: the ColorChecker under a light through the band pipeline, against the tool's own 1 nm colorimetry.</summary>
public static class ColorsCommand
{
    const string Help = """
        usage: spectral colors [--illuminant NAME] [--observer 2|10] [--bands 380:780:20 | --wave 390:20:770]
                               [--integration exact|weighted|paper] [--rgb srgb|paper] [--csv]

        Prints the 24 ColorChecker patches (Ohta reflectances) lit by a light: XYZ (white Y = 1),
        CIELAB, linear RGB and 8-bit RGB, computed with the band scheme, and each patch's
        CIEDE2000 difference from the 1 nm computation, with mean and max.

          --illuminant NAME   D65 (default), A, D50, E, FL2, FL11, led-blue, led-green, led-rgb,
                              led-yag, or file.csv:column
          --observer 2|10     CIE 1931 2° (default) or CIE 1964 10°
          --bands S:E:N       band edges, default 380:780:20
          --wave S:STEP:E     or band centres, each STEP wide (390:20:770 is the same 20 bands)
          --integration       exact (default: ∫x̄·E·R dλ on the full tables), weighted (spectral
                              prefiltering) or paper (eq. 3 with band means)
          --rgb srgb|paper    sRGB (IEC 61966-2-1, default) or the paper's eq. 4 matrix
          --csv               machine-readable CSV instead of a table
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("colors", argv, ["--illuminant", "--observer", "--bands", "--wave", "--integration", "--rgb"], ["--csv"]);
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count > 0)
            throw new InputException("colors", $"unexpected argument {MessageText.Quote(a.Positionals[0])}",
                "see 'spectral colors --help'");

        var lightName = a.Value("--illuminant") ?? "D65";
        var light = SpectrumLibrary.Resolve(lightName, Directory.GetCurrentDirectory(), "--illuminant");
        var observer = Observer.FromDegrees(a.Value("--observer") ?? "2");
        if (a.Value("--bands") is not null && a.Value("--wave") is not null)
            throw new InputException("--wave", "--wave and --bands both give the bands",
                "use one: --wave 390:20:770 (centres) or --bands 380:780:20 (edges)");
        var grid = a.Value("--wave") is { } wave ? BandGrid.ParseWave(wave) : BandGrid.Parse(a.Value("--bands") ?? "380:780:20");
        var scheme = ParseScheme(a.Value("--integration") ?? "exact", "--integration");
        var rgb = RgbSpace.Parse(a.Value("--rgb") ?? "srgb");
        light.RequireCoverage(grid.Start, grid.End, "--illuminant");
        for (int p = 1; p <= ColorChecker.PatchCount; p++) ColorChecker.Patch(p).RequireCoverage(grid.Start, grid.End, "--bands");

        var bands = new Colorimeter(grid, observer, light, scheme);
        var reference = new ReferenceColorimeter(observer, light, grid.Start, grid.End);
        var inv = CultureInfo.InvariantCulture;
        bool csv = a.Flag("--csv");
        if (csv) stdout.WriteLine("patch,name,X,Y,Z,L,a,b,r_linear,g_linear,b_linear,r8,g8,b8,dE00_vs_1nm");
        else
        {
            stdout.WriteLine($"ColorChecker (Ohta) under {light.Name}, {observer.Name} observer, bands {grid} ({grid.Width:0.###} nm), "
                + $"{scheme.ToString().ToLowerInvariant()} integration, {rgb.Name} RGB");
            stdout.WriteLine($"{"#",2} {"name",-18} {"X",8} {"Y",8} {"Z",8} {"L*",7} {"a*",7} {"b*",7} {"R",7} {"G",7} "
                + $"{"B",7}  {"RGB8",-11} {"ΔE00",6}");
        }
        double sum = 0, max = 0;
        for (int p = 1; p <= ColorChecker.PatchCount; p++)
        {
            var patch = ColorChecker.Patch(p);
            var xyz = bands.OfReflectance(patch);
            var lab = Lab.FromXyz(xyz, reference.White);
            var exact = Lab.FromXyz(reference.OfReflectance(patch), reference.White);
            double de = DeltaE2000.Between(lab, exact);
            sum += de; max = Math.Max(max, de);
            var (r, g, b) = rgb.Linear(xyz);
            var c8 = rgb.Encode8(xyz);
            var name = ColorChecker.Name(p);
            if (csv)
                stdout.WriteLine(string.Create(inv,
                    $"{p},{name},{xyz.X:R},{xyz.Y:R},{xyz.Z:R},{lab.L:R},{lab.A:R},{lab.B:R},{r:R},{g:R},"
                        + $"{b:R},{c8.R},{c8.G},{c8.B},{de:R}"));
            else
                stdout.WriteLine(string.Create(inv,
                    $"{p,2} {Trunc(name, 18),-18} {xyz.X,8:F5} {xyz.Y,8:F5} {xyz.Z,8:F5} {lab.L,7:F2} {lab.A,7:F2} {lab.B,7:F2} {r,7:F4} "
                        + $"{g,7:F4} {b,7:F4}  {c8.R,3} {c8.G,3} {c8.B,3} {de,6:F3}"));
        }
        if (!csv) stdout.WriteLine(string.Create(inv, $"ΔE00 against 1 nm integration: mean {sum / 24:F3}, max {max:F3}"));
        return CommandLine.Success;
    }

    static string Trunc(string s, int n) => s.Length <= n ? s : s[..n];

    public static BandIntegration ParseScheme(string s, string where) => BandIntegrations.Parse(s, where);
}
