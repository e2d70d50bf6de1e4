using System.Globalization;
using SpectralRenderer.Analysis;
using SpectralRenderer.Color;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Cli.Commands;

/// <summary>`spectral colorcheck OUTDIR`: the rendered ColorChecker patches against their 1 nm reference (§3.1).</summary>
public static class ColorCheckCommand
{
    const string Help = """
        usage: spectral colorcheck OUTDIR [--csv]

        Averages each ColorChecker patch's pixels in a render (found by object id) and prints its XYZ,
        CIELAB, 8-bit sRGB and the CIEDE2000 difference from the patch's reflectance under the scene's
        reference white integrated at 1 nm, with mean and max. Needs render.json, object-id.png and a
        spectral cube (spectral.npy, .exr or .img) in OUTDIR.
        """;

    public static int Run(string[] argv, TextWriter stdout, TextWriter stderr)
    {
        var a = new Arguments("colorcheck", argv, [], ["--csv"]);
        if (a.Help) { stdout.WriteLine(Help); return CommandLine.Success; }
        if (a.Positionals.Count != 1)
            throw new InputException("command line", "give one render folder", "usage: spectral colorcheck OUTDIR");
        var folder = RenderFolder.Open(a.Positionals[0]);
        var rows = ColorCheckerReport.Compute(folder);
        if (rows.Count == 0)
            throw new InputException(a.Positionals[0], "shows no ColorChecker patch",
                "render a scene with colorchecker materials, e.g. scenes/paper-3.1-colorchecker-d65.json");
        var inv = CultureInfo.InvariantCulture;
        if (a.Flag("--csv"))
        {
            stdout.WriteLine("patch,object,pixels,X,Y,Z,L,a,b,srgb8_r,srgb8_g,srgb8_b,ref_X,ref_Y,ref_Z,ref_L,ref_a,ref_b,dE00");
            foreach (var r in rows)
                stdout.WriteLine(string.Create(inv,
                    $"{r.Patch},{r.Object},{r.Pixels},{r.Rendered.X:R},{r.Rendered.Y:R},{r.Rendered.Z:R},{r.RenderedLab.L:R},"
                        + $"{r.RenderedLab.A:R},{r.RenderedLab.B:R},{r.Srgb8.R},{r.Srgb8.G},{r.Srgb8.B},{r.Reference.X:R},"
                        + $"{r.Reference.Y:R},{r.Reference.Z:R},{r.ReferenceLab.L:R},{r.ReferenceLab.A:R},"
                        + $"{r.ReferenceLab.B:R},{r.DeltaE00:R}"));
            return CommandLine.Success;
        }
        stdout.WriteLine($"ColorChecker in {folder.Path}: {folder.Image.Grid} bands, {BandIntegrations.Name(folder.Integration)} "
            + $"integration, reference white {folder.ReferenceWhite.Name}, {folder.ObserverDegrees}° observer; reference: 1 nm");
        stdout.WriteLine($"{"#",2} {"name",-18} {"pixels",7} {"X",8} {"Y",8} {"Z",8} {"L*",7} {"a*",7} {"b*",7}  {"sRGB8",-11} "
            + $"{"ref L*",7} {"ref a*",7} {"ref b*",7} {"ΔE00",6}");
        foreach (var r in rows)
            stdout.WriteLine(string.Create(inv,
                $"{r.Patch,2} {Spectra.ColorChecker.Name(r.Patch)[..Math.Min(18, Spectra.ColorChecker.Name(r.Patch).Length)],-18} "
                    + $"{r.Pixels,7} {r.Rendered.X,8:F5} {r.Rendered.Y,8:F5} {r.Rendered.Z,8:F5} {r.RenderedLab.L,7:F2} "
                    + $"{r.RenderedLab.A,7:F2} {r.RenderedLab.B,7:F2}  {r.Srgb8.R,3} {r.Srgb8.G,3} {r.Srgb8.B,3} {r.ReferenceLab.L,7:F2} "
                    + $"{r.ReferenceLab.A,7:F2} {r.ReferenceLab.B,7:F2} {r.DeltaE00,6:F3}"));
        stdout.WriteLine(string.Create(inv,
            $"ΔE00 against 1 nm: mean {rows.Average(r => r.DeltaE00):F3}, max {rows.Max(r => r.DeltaE00):F3} over {rows.Count} patches"));
        return CommandLine.Success;
    }
}
