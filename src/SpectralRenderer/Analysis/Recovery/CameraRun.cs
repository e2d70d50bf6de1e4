using System.Text.Json.Nodes;
using SpectralRenderer.Sensor;

namespace SpectralRenderer.Analysis.Recovery;

/// <summary>
/// One camera run on a render (docs/camera.md): the sensor simulation, the colour fit, the image processing, the chart's
/// patch metrics and camera.json's content — the steps `spectral camera` (CameraCommand) and libspectral's
/// spectral_camera (NativeCapture) share, so both record the same fields in the same order.
/// </summary>
public sealed record CameraRun(RawFrame Raw, ColourCorrection Colour, ProcessedImage Image, List<PatchMetrics> Patches,
    JsonObject Manifest)
{
    /// <summary>The white scale without the exact route: the reference white's band values as they are.</summary>
    public const string PaperWhite = "1: the light's band values (the paper's white; the render's eq. 2 terms were not used)";

    /// <summary>
    /// Runs the camera on <paramref name="cube"/> (the band cube, or with the exact route's channel integrals) of
    /// <paramref name="scene"/>. <paramref name="scaleOption"/> names the option the radiance scale was given with (null:
    /// the default 1); <paramref name="sensorArgument"/> and <paramref name="renderFolder"/> (null: none) are recorded as given.
    /// </summary>
    public static CameraRun Run(CameraScene scene, SensorModel sensor, RadianceCube cube, SimulationOptions options,
        DemosaicMethod demosaic, double whiteScale, string whiteSource, string? scaleOption, string sensorArgument,
        string? renderFolder)
    {
        var raw = SensorSimulation.Run(sensor, cube, scene.Light, options);
        var colour = ColourCorrection.Fit(raw.Weights, scene.Grid, scene.Light, scene.Observer,
            cube.ChannelIntegrals is null ? null : sensor, whiteScale);
        var image = ImageProcessing.Run(raw, colour, demosaic);
        var patches = CameraPatchMetrics.Compute(scene, raw, image, colour);

        bool relative = scene.Radiometry != "physical";
        var manifest = CameraManifest.Build(raw, colour, scene.Grid, scene.LightName, cube.RadianceScale,
            scaleOption is not null ? $"given with {scaleOption}"
            : relative ? "default 1: the render's radiometry is relative (the paper's eq. 2 has no units), so its band values are "
                + "taken as W·m⁻²·sr⁻¹·nm⁻¹"
            : "default 1: the render's physical radiometry is in W·m⁻²·sr⁻¹·nm⁻¹", cube.Route, whiteSource);
        manifest["sensor_argument"] = sensorArgument;
        if (renderFolder is not null) manifest["render_folder"] = renderFolder;
        manifest["render_radiometry"] = scene.Radiometry ?? "paper";
        var (clipTop, clipBottom) = raw.ClippedFractions();
        manifest["simulation"]!["clipped_at_white_fraction"] = clipTop;
        manifest["simulation"]!["clipped_below_black_fraction"] = clipBottom;
        manifest["processing"]!["demosaic"] = image.Demosaicked?.ToString().ToLowerInvariant();
        manifest["patches"] = new JsonArray(patches.Select(p => (JsonNode)new JsonObject
        {
            ["patch"] = p.Patch,
            ["object"] = p.Object,
            ["pixels"] = p.Pixels,
            ["camera_xyz"] = new JsonArray(p.Camera.X, p.Camera.Y, p.Camera.Z),
            ["exact_xyz"] = new JsonArray(p.Exact.X, p.Exact.Y, p.Exact.Z),
            ["delta_e00"] = p.DeltaE00,
            ["snr_db"] = new JsonArray(p.SnrDb.Select(v => double.IsFinite(v) ? (JsonNode?)v : null).ToArray()),
        }).ToArray());
        return new CameraRun(raw, colour, image, patches, manifest);
    }
}
