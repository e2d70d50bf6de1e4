namespace SpectralRenderer.Output;

/// <summary>
/// render.json's "run": how the render was produced. Written by <see cref="RenderManifest.ToJson"/> in this order, a
/// null property left out (except <see cref="Overrides"/> where <see cref="HasOverrides"/> says it is recorded).
/// </summary>
public sealed record ManifestRun
{
    public string? CommandLine { get; init; }
    /// <summary>The integrator the command line chose (<c>--integrator</c>); null: the resolved scene's, else whitted.</summary>
    public string? Integrator { get; init; }
    /// <summary>`spectral merge`: how many shards were assembled.</summary>
    public int? MergedShards { get; init; }
    /// <summary>`spectral sweep`: the job's id.</summary>
    public string? SweepJob { get; init; }
    /// <summary>Wall seconds to read the scene and its meshes.</summary>
    public double? LoadSeconds { get; init; }
    /// <summary>Wall seconds to build the BVHs and the integrator.</summary>
    public double? BuildSeconds { get; init; }
    public int? Triangles { get; init; }
    public int? DegenerateTrianglesSkipped { get; init; }
    public double? MinRayWeight { get; init; }
    public int? RayBudget { get; init; }
    public long? RaysPrunedByWeight { get; init; }
    public long? CameraRaysOverBudget { get; init; }
    /// <summary>The shard this folder is ("I/N (source)").</summary>
    public string? Shard { get; init; }
    /// <summary>Wall seconds of the per-light transfer (lights/).</summary>
    public double? LightTransferSeconds { get; init; }
    /// <summary>Whether "overrides" is recorded (null then writes as JSON null).</summary>
    public bool HasOverrides { get; init; }
    /// <summary>The command-line overrides the scene was loaded with (relight rebuilds the same scene from them).</summary>
    public ManifestOverrides? Overrides { get; init; }
    /// <summary>A relit render: what it was relit from and how.</summary>
    public ManifestRelit? Relit { get; init; }
    /// <summary>Wall seconds from the pixels to every file but render.json written.</summary>
    public double? WriteSeconds { get; init; }
    /// <summary>A scene of another renderer's format converted in memory (docs/import.md): its import report, { "source",
    /// "format", "entries" }.</summary>
    public System.Text.Json.Nodes.JsonObject? Imported { get; init; }
}

/// <summary>The command-line overrides of a render as render.json records them ("run.overrides"); null: the scene's own.</summary>
public sealed record ManifestOverrides(int? Width, int? Height, string? Bands, string? Wave, int? SamplesPerPixel, string? Rgb,
    string? Integration, string? Formats, string? ExrCompression, IReadOnlyList<string> Models, string? Exposure = null);

/// <summary>A light's change in a relight: its new spectrum and/or intensity (null: kept).</summary>
public sealed record ManifestLightChange(string Light, string? Spectrum, double? Intensity);

/// <summary>"run.relit": the source folder of a relit render, the changes and what was copied rather than written.</summary>
public sealed record ManifestRelit
{
    public required string From { get; init; }
    public required string FromCreatedUtc { get; init; }
    public required string Method { get; init; }
    public required IReadOnlyList<ManifestLightChange> Changes { get; init; }
    public string? White { get; init; }
    /// <summary>Wall seconds to read lights/ and recombine the image and its colours (no files written).</summary>
    public double ComputeSeconds { get; init; }
    public RelightMetrics? Metrics { get; init; }
    /// <summary>The files copied from the source (no light changes them), not encoded again.</summary>
    public IReadOnlyList<string>? CopiedFiles { get; init; }
}

/// <summary>A relit light's colour rendering (CIE 13.3 Ra, CIE 224:2017 Rf, CCT), null where undefined.</summary>
public sealed record RelightLightMetrics(string Light, string? Spectrum, double? Ra, double? Rf, double? CctKelvin);

/// <summary>An object's ΔE00 between the source and the relit render over the pixels that see it.</summary>
public sealed record RelightObjectMetrics(string Object, int Pixels, double MeanDeltaE00, double MaxDeltaE00);

/// <summary>"run.relit.metrics" (relight --metrics).</summary>
public sealed record RelightMetrics(string White, IReadOnlyList<RelightLightMetrics> Lights, IReadOnlyList<RelightObjectMetrics> Objects);
