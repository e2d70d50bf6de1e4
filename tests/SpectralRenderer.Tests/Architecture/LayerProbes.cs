// The engine's layers mirrored under SpectralRenderer.Tests.Architecture.Probe.Layers (LayeringTests.Allowed re-rooted
// there): each layer has a Mark, and each layer but Cli one deliberate back edge (BackEdge) into a layer its rule does
// not allow, so every layer is once the source and once the target of a back edge (Diagnostics, which all may use, only
// the source; Cli, which may use all, only the target). Every back edge goes through what the compiler folds away — a
// constant, an enum value, nameof, a default parameter value, a case label, a using static or alias — so none is in
// the IL and only the source reader can see it; the compiler checks that each name binds as written.
namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Diagnostics
{
    public static class Mark { public const int Value = 1; }

    static class BackEdge { public const int X = Spectra.Mark.Value; }   // qualified from an enclosing namespace
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Spectra
{
    public static class Mark { public const int Value = 2; }

    static class BackEdge { public const int X = global::SpectralRenderer.Tests.Architecture.Probe.Layers.Color.Mark.Value; }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Color
{
    public static class Mark { public const int Value = 3; }

    static class BackEdge { public const int X = SpectralRenderer.Tests.Architecture.Probe.Layers.Geometry.Mark.Value; }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Geometry
{
    using static SpectralRenderer.Tests.Architecture.Probe.Layers.Acceleration.Mark;

    public static class Mark { public const int Value = 4; }

    static class BackEdge { public const int X = Value; }   // through the using static
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Acceleration
{
    public static class Mark { public const int Value = 5; }

    static class BackEdge { public const int X = (int)Scenes.Kind.Light; }   // an enum value
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Scenes
{
    public static class Mark { public const int Value = 6; }

    public enum Kind { Object, Light }

    static class BackEdge { public const int X = Loading.Mark.Value; }   // a nested layer, named from its parent
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Scenes.Loading
{
    public static class Mark { public const int Value = 7; }

    static class BackEdge { public const string X = nameof(Rendering.Mark.Value); }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Scenes.Import
{
    public static class Mark { public const int Value = 18; }

    static class BackEdge { public const int X = Loading.Mark.Value; }   // an importer writes JSON; it never loads a scene
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Rendering
{
    using Writer = SpectralRenderer.Tests.Architecture.Probe.Layers.Output.Mark;

    public static class Mark { public const int Value = 8; }

    static class BackEdge { public const int X = Writer.Value; }   // through a using alias
}

// Rendering's wings: Whitted and the path tracer never use each other; the terms, the emitters and the film use neither.
namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Rendering.Terms
{
    public static class Mark { public const int Value = 18; }

    static class BackEdge { public const int X = Whitted.Mark.Value; }   // a sibling wing, named from the enclosing namespace
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Rendering.Emitters
{
    public static class Mark { public const int Value = 19; }

    static class BackEdge { public const string X = nameof(PathTracing.Mark); }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Rendering.Whitted
{
    public static class Mark { public const int Value = 20; }

    static class BackEdge
    {
        public const int X = global::SpectralRenderer.Tests.Architecture.Probe.Layers.Rendering.PathTracing.Mark.Value;
    }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Rendering.PathTracing
{
    using static SpectralRenderer.Tests.Architecture.Probe.Layers.Rendering.Whitted.Mark;

    public static class Mark { public const int Value = 21; }

    static class BackEdge { public const int X = Value; }   // through the using static
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Rendering.Illumination
{
    public static class Mark { public const int Value = 22; }

    static class BackEdge { public const int X = Rendering.Registry.Mark.Value; }   // photometry gathers from the integrator it is given
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Rendering.Registry
{
    public static class Mark { public const int Value = 23; }

    static class BackEdge { public const int X = Output.Mark.Value; }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Imaging
{
    public static class Mark { public const int Value = 9; }

    static class BackEdge { public const int X = Sensor.Mark.Value; }   // a codec reading the sensor's constant
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Sensor
{
    public static class Mark { public const int Value = 10; }

    static class BackEdge
    {
        public static bool IsOutput(int v) => v switch { Output.Mark.Value => true, _ => false };   // a case label
    }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Output
{
    public static class Mark { public const int Value = 11; }

    static class BackEdge
    {
        public static int Of(int x = Pipeline.Mark.Value) => x;   // a default parameter value
    }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Pipeline
{
    public static class Mark { public const int Value = 12; }

    static class BackEdge { public const string X = $"{Analysis.Mark.Name}"; }   // a constant interpolated string
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Analysis
{
    public static class Mark { public const int Value = 13; public const string Name = "analysis"; }

    static class BackEdge { public static readonly int X = Relighting.Mark.Value; }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Relighting
{
    public static class Mark { public const int Value = 14; }

    static class BackEdge { public const int X = Distributed.Mark.Value + 1; }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Distributed
{
    public static class Mark { public const int Value = 15; }

    static class BackEdge { public const int X = Cli.Mark.Value; }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Validation
{
    public static class Mark { public const int Value = 18; }

    static class BackEdge { public static string X => nameof(Cli.Mark); }   // nameof: the validation cases never use the CLI
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Cli
{
    public static class Mark { public const int Value = 16; }
}

namespace SpectralRenderer.Tests.Architecture.Probe.Layers.Native
{
    public static class Mark { public const int Value = 17; }

    static class BackEdge { public const int X = -Cli.Mark.Value; }   // libspectral's C ABI uses the engine, not the CLI
}
