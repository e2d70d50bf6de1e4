// Three tiny namespaces for LayeringTests: High uses ByUsing through a using directive and ByName only
// by its fully qualified name, so the dependency reader must see both kinds of reference.
namespace SpectralRenderer.Tests.Architecture.Probe.ByUsing
{
    public readonly record struct Pair(int A, int B);
}

namespace SpectralRenderer.Tests.Architecture.Probe.ByName
{
    public static class Twice
    {
        public static int Of(int x) => 2 * x;
    }
}

namespace SpectralRenderer.Tests.Architecture.Probe.High
{
    using SpectralRenderer.Tests.Architecture.Probe.ByUsing;

    public static class Sum
    {
        public static int Of(Pair p) => global::SpectralRenderer.Tests.Architecture.Probe.ByName.Twice.Of(p.A) + p.B;
    }
}
