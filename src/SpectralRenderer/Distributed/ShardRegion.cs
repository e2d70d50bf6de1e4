using SpectralRenderer.Diagnostics;
using SpectralRenderer.Pipeline;

namespace SpectralRenderer.Distributed;

/// <summary>The film pixels a render's options ask for: --crop, --shard I/N, or a job array task's shard.</summary>
public static class ShardRegion
{
    /// <summary>
    /// The region of <paramref name="options"/> (null: the whole film) and the shard's description for render.json. Without
    /// --crop or --shard, a job array task's variables give the shard when <paramref name="jobArray"/> (the command line;
    /// <see cref="SchedulerEnvironment"/>); the C ABI reads none (a library call is not a task of an array).
    /// </summary>
    public static RenderRegion? Of(RenderOptionValues options, bool jobArray)
    {
        string? crop = options.Crop, shard = options.Shard;
        int? shards = options.Shards;
        if (crop is not null && shard is not null)
            throw new InputException("--crop", "cannot be combined with --shard", "a shard is a crop: give one of them");
        if (crop is not null) return RenderRegion.Crop(crop);
        if (shard == "none") return null;
        if (shard is not null)
        {
            var s = Shard.Parse(shard);
            if (shards is { } n && n != s.Count)
                throw new InputException("--shards", $"{n} disagrees with --shard {shard}",
                    "give --shard I/N alone, or --shards N equal to its N");
            return new RenderRegion(s.Strip, $"{s} (--shard)");
        }
        if (jobArray && SchedulerEnvironment.Resolve(shards) is { } env)
            return new RenderRegion((w, h) => env.Shard.Strip(w, h, $"{env.Source} job array task {env.Shard}"),
                $"{env.Shard} ({env.Source})");
        if (shards is not null)
            throw new InputException("--shards", "is given but no job array variable is set", "use --shard I/N outside a job array");
        return null;
    }
}
