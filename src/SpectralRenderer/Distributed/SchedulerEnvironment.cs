using System.Globalization;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Distributed;

/// <summary>
/// The shard a job-array task is, read from the variables the schedulers set in every task:
/// <list type="bullet">
/// <item>Slurm (sbatch --array, "Job Array Support"): SLURM_ARRAY_TASK_ID with SLURM_ARRAY_TASK_MIN, _MAX and _STEP
/// (index (ID − MIN) / STEP of (MAX − MIN) / STEP + 1), or SLURM_ARRAY_TASK_COUNT when MAX is absent;</item>
/// <item>Kubernetes Indexed Jobs (completionMode: Indexed): JOB_COMPLETION_INDEX; Kubernetes sets no count, so it is
/// the <c>--shards N</c> option (the Job's completions);</item>
/// <item>AWS Batch array jobs: AWS_BATCH_JOB_ARRAY_INDEX with AWS_BATCH_JOB_ARRAY_SIZE (or <c>--shards N</c>).</item>
/// </list>
/// The first scheduler whose index variable is set wins, in that order.
/// </summary>
public static class SchedulerEnvironment
{
    /// <summary>The shard from the environment, or null when no scheduler's index variable is set.</summary>
    /// <param name="shards">The count given with --shards, if any (required for Kubernetes; checked against the others).</param>
    /// <param name="env">Variable lookup (Environment.GetEnvironmentVariable by default).</param>
    public static (Shard Shard, string Source)? Resolve(int? shards, Func<string, string?>? env = null)
    {
        env ??= Environment.GetEnvironmentVariable;
        if (Get(env, "SLURM_ARRAY_TASK_ID") is { } id) return (Slurm(id, shards, env), "Slurm");
        if (Get(env, "JOB_COMPLETION_INDEX") is { } k)
        {
            if (shards is null)
                throw new InputException("JOB_COMPLETION_INDEX", $"is {k} but Kubernetes sets no task count",
                    "pass --shards N, the Job's spec.completions");
            return (Shard.Checked(k, shards.Value, $"JOB_COMPLETION_INDEX={k} with --shards {shards}"), "Kubernetes");
        }
        if (Get(env, "AWS_BATCH_JOB_ARRAY_INDEX") is { } a)
        {
            int? size = Get(env, "AWS_BATCH_JOB_ARRAY_SIZE");
            int count = Agree(size, shards, "AWS_BATCH_JOB_ARRAY_SIZE")
                ?? throw new InputException("AWS_BATCH_JOB_ARRAY_INDEX", $"is {a} but AWS_BATCH_JOB_ARRAY_SIZE is not set",
                    "pass --shards N, the array job's size");
            return (Shard.Checked(a, count, $"AWS_BATCH_JOB_ARRAY_INDEX={a} of AWS_BATCH_JOB_ARRAY_SIZE={count}"), "AWS Batch");
        }
        return null;
    }

    static Shard Slurm(int id, int? shards, Func<string, string?> env)
    {
        int min = Get(env, "SLURM_ARRAY_TASK_MIN") ?? 0;
        int step = Get(env, "SLURM_ARRAY_TASK_STEP") ?? 1;
        int? max = Get(env, "SLURM_ARRAY_TASK_MAX");
        int? taskCount = Get(env, "SLURM_ARRAY_TASK_COUNT");
        if (step < 1)
            throw new InputException("SLURM_ARRAY_TASK_STEP", $"is {step}, not at least 1",
                "the array step must be a positive whole number (sbatch --array=0-9:2)");
        if ((id - min) % step != 0 || id < min)
            throw new InputException("SLURM_ARRAY_TASK_ID", $"{id} is not SLURM_ARRAY_TASK_MIN {min} + k·STEP {step}",
                "shards need a regular array such as --array=0-3 or 0-30:10");
        int? fromRange = max is { } m ? (m - min) / step + 1 : null;
        if (fromRange is { } r && taskCount is { } c && r != c)
            throw new InputException("SLURM_ARRAY_TASK_COUNT", $"{c} tasks but MIN {min}, MAX {max}, STEP {step} make {r}",
                "shards need a regular array such as --array=0-3, not a list");
        int count = Agree(fromRange ?? taskCount, shards, "the Slurm array's task count")
            ?? throw new InputException("SLURM_ARRAY_TASK_ID",
                $"is {id} but neither SLURM_ARRAY_TASK_MAX nor SLURM_ARRAY_TASK_COUNT is set",
                "pass --shards N");
        return Shard.Checked((id - min) / step, count, $"SLURM_ARRAY_TASK_ID={id} (min {min}, step {step}, {count} tasks)");
    }

    static int? Agree(int? fromScheduler, int? shards, string what)
    {
        if (fromScheduler is { } s && shards is { } n && s != n)
            throw new InputException("--shards", $"{n} disagrees with {what} {s}", "leave --shards out: the scheduler gives the count");
        return fromScheduler ?? shards;
    }

    /// <summary>A whole number written with a sign and digits only, of any size.</summary>
    static bool IsDigits(string v) => v.TrimStart('-', '+') is { Length: > 0 } d && d.All(char.IsAsciiDigit);

    static int? Get(Func<string, string?> env, string name)
    {
        var v = env(name);
        if (string.IsNullOrWhiteSpace(v)) return null;
        if (!int.TryParse(v.Trim(), NumberStyles.AllowLeadingSign, CultureInfo.InvariantCulture, out int n))
            throw new InputException(name,
                IsDigits(v.Trim())
                    ? $"{MessageText.Quote(v)} is beyond the ±{int.MaxValue} a job array index can be"
                    : $"{MessageText.Quote(v)} is not a whole number",
                "it is set by the scheduler; unset it outside a job array");
        return n;
    }
}
