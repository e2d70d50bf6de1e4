using System.Numerics;
using System.Text.Json;

namespace SpectralRenderer.Scenes.Loading;

// The camera: position, look_at, up, fov, resolution (with the command line's overrides), samples per pixel.
public sealed partial class SceneLoader
{
    Camera ParseCamera(JsonElement e, string path)
    {
        Object(e, path);
        // sensor: read by `spectral camera` (Sensor/SensorFile.FromScene)
        Keys(e, path, "position", "look_at", "up", "fov", "width", "height", "spp", "target_error", "sensor");
        var position = Vec3(Required(e, "position", path), $"{path}.position");
        var lookAt = Vec3(Required(e, "look_at", path), $"{path}.look_at");
        var up = Vec3(e, "up", path, Vector3.UnitY);
        if (lookAt == position) throw Error($"{path}.look_at", "look_at equals position", "the camera needs a direction to look in");
        if (Vector3.Cross(Vector3.Normalize(lookAt - position), up).LengthSquared() < 1e-12f)
            throw Error($"{path}.up", "up is parallel to the viewing direction", "choose another up vector");
        float fov = (float)Number(e, "fov", path, 40, 1e-3, 179);
        int sceneWidth = Integer(e, "width", path, 640, int.MinValue, int.MaxValue);
        int sceneHeight = Integer(e, "height", path, 480, int.MinValue, int.MaxValue);
        int width = _overrides.Width ?? sceneWidth, height = _overrides.Height ?? sceneHeight;
        // One side given alone keeps the camera's aspect ratio (the field of view is vertical, so the view widens or narrows with it
        // otherwise).
        if (sceneWidth > 0 && sceneHeight > 0)
        {
            if (_overrides.Width is { } ow && _overrides.Height is null && ow > 0)
                height = Math.Max(1, (int)Math.Round((double)ow * sceneHeight / sceneWidth, MidpointRounding.AwayFromZero));
            else if (_overrides.Height is { } oh && _overrides.Width is null && oh > 0)
                width = Math.Max(1, (int)Math.Round((double)oh * sceneWidth / sceneHeight, MidpointRounding.AwayFromZero));
        }
        if (_overrides.ResolutionScale != 1 && width > 0 && height > 0)
        {
            width = Math.Max(8, (int)Math.Round(width * _overrides.ResolutionScale));
            height = Math.Max(8, (int)Math.Round(height * _overrides.ResolutionScale));
        }
        if (width < 1 || height < 1)
            throw Error(width < 1 ? $"{path}.width" : $"{path}.height", $"resolution {width}×{height} is not positive",
                "width and height must be at least 1");
        if (width > MaxResolution || height > MaxResolution)
            throw Error(width > MaxResolution ? $"{path}.width" : $"{path}.height",
                $"resolution {width}×{height} exceeds {MaxResolution} pixels on a side", "lower the width or height");
        int spp = _overrides.SamplesPerPixel ?? Integer(e, "spp", path, 1, 1, 65536);
        // Adaptive sampling: each pixel stops at this relative standard error of its luminance (spp the cap); 0 is off.
        _targetError = _overrides.TargetError ?? Number(e, "target_error", path, 0, 0, 1);
        if (_targetError > 0 && spp < 2)
            throw Error(_overrides.TargetError is null ? $"{path}.target_error" : "--target-error",
                $"adaptive sampling needs spp of at least 2 as its cap, found {spp}",
                    "give \"spp\" (or --spp) the most samples a pixel may take, e.g. 256");
        return new Camera(position, lookAt, up, fov, width, height, spp);
    }
}
