using System.Numerics;

namespace SpectralRenderer.Validation;

/// <summary>
/// Test hook (set only by tests): one deliberate error, so that the report must fail exactly the cases that depend on
/// it — fed into what the cases hand the engine (not their references): a light's spectrum scaled (every
/// light, emitter and sky the cases build), the receivers' cos θ (their normals tilted), or the CMF table (read some
/// nanometres off by the colour cases' 1 nm summation: the engine's observer is fixed by the scene file, so this one
/// goes into the reference side). Held per asynchronous flow, so tests run side by side unaffected.
/// </summary>
internal static class Perturbation
{
    internal sealed record Settings(double LightScale = 1, double ReceiverTiltDegrees = 0, double CmfShiftNm = 0);

    static readonly AsyncLocal<Settings?> Current = new();

    /// <summary>Sets the perturbation for the calling flow until the result is disposed.</summary>
    internal static IDisposable Set(Settings settings)
    {
        var before = Current.Value;
        Current.Value = settings;
        return new Restore(before);
    }

    sealed class Restore(Settings? before) : IDisposable
    {
        public void Dispose() => Current.Value = before;
    }

    /// <summary>The factor on every light's, emitter's and sky's value a case writes into its scene (1: none).</summary>
    internal static double LightScale => Current.Value?.LightScale ?? 1;

    /// <summary>How many nanometres off the colour cases' summation reads the CMFs (0: none).</summary>
    internal static double CmfShiftNm => Current.Value?.CmfShiftNm ?? 0;

    /// <summary>A receiver's normal as a case hands it to the engine: tilted by the perturbation's angle (0: unchanged).</summary>
    internal static Vector3 Receiver(Vector3 n)
    {
        double tilt = Current.Value?.ReceiverTiltDegrees ?? 0;
        if (tilt == 0) return n;
        // About a horizontal axis across n: a vertical receiver leans up, a horizontal one sideways.
        var axis = Vector3.Normalize(Vector3.Cross(n, MathF.Abs(n.Y) < 0.9f ? Vector3.UnitY : Vector3.UnitX));
        return Vector3.Normalize(Vector3.Transform(n, Quaternion.CreateFromAxisAngle(axis, (float)(tilt * Math.PI / 180))));
    }
}
