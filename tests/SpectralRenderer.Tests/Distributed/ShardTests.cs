using SpectralRenderer.Diagnostics;
using SpectralRenderer.Distributed;
using SpectralRenderer.Rendering;

namespace SpectralRenderer.Tests.Distributed;

/// <summary>Shard strips and the schedulers' array variables (values as a real Slurm 22.05 sets them, tests/slurm).</summary>
public class ShardTests
{
    [Theory]
    [InlineData(1024, 1024, 4)]
    [InlineData(640, 480, 4)]
    [InlineData(100, 33, 2)]
    [InlineData(4096, 4096, 16)]
    [InlineData(64, 1000, 7)]
    public void Strips_cover_every_row_once_on_tile_and_exr_chunk_boundaries(int w, int h, int n)
    {
        var rows = new int[h];
        var strips = Enumerable.Range(0, n).Select(i => new Shard(i, n).Strip(w, h)).ToList();
        foreach (var s in strips)
        {
            Assert.Equal(0, s.X0);
            Assert.Equal(w, s.X1);
            Assert.Equal(0, s.Y0 % Renderer.TileSize);   // whole tile rows
            Assert.Equal(0, s.Y0 % 16);                  // whole OpenEXR ZIP chunks (16 scanlines)
            Assert.True(s.Height > 0);
            for (int y = s.Y0; y < s.Y1; y++) rows[y]++;
        }
        Assert.All(rows, c => Assert.Equal(1, c));
        // Balanced: strip heights differ by at most one tile row.
        var heights = strips.Take(n - 1).Select(s => s.Height / Renderer.TileSize).ToList();
        Assert.True(heights.Max() - heights.Min() <= 1);
    }

    [Fact]
    public void More_shards_than_tile_rows_is_bad_input()
    {
        var e = Assert.Throws<InputException>(() => new Shard(0, 5).Strip(64, 100));   // 4 tile rows
        Assert.Contains("at most 4 shards", e.Message);
    }

    [Theory]
    [InlineData("0/4", 0, 4)]
    [InlineData("3/4", 3, 4)]
    public void Shard_parses_I_of_N(string text, int i, int n) => Assert.Equal(new Shard(i, n), Shard.Parse(text));

    [Theory]
    [InlineData("4/4")]
    [InlineData("1")]
    [InlineData("-1/4")]
    [InlineData("a/b")]
    [InlineData("0/0")]
    public void Bad_shard_text_is_one_line_of_bad_input(string text)
    {
        var e = Assert.Throws<InputException>(() => Shard.Parse(text));
        Assert.DoesNotContain('\n', e.Message);
    }

    static Func<string, string?> Env(params (string, string)[] vars)
    {
        var d = vars.ToDictionary(v => v.Item1, v => v.Item2);
        return k => d.TryGetValue(k, out var v) ? v : null;
    }

    [Theory]   // sbatch --array=0-3 and --array=10-40:10, as Slurm 22.05 set them in tests/slurm
    [InlineData("0", "0", "3", "1", "4", 0, 4)]
    [InlineData("2", "0", "3", "1", "4", 2, 4)]
    [InlineData("10", "10", "40", "10", "4", 0, 4)]
    [InlineData("30", "10", "40", "10", "4", 2, 4)]
    public void Slurm_array_task_is_its_index_in_the_range(string id, string min, string max, string step, string count, int i, int n)
    {
        var r = SchedulerEnvironment.Resolve(null, Env(("SLURM_ARRAY_TASK_ID", id), ("SLURM_ARRAY_TASK_MIN", min),
            ("SLURM_ARRAY_TASK_MAX", max), ("SLURM_ARRAY_TASK_STEP", step), ("SLURM_ARRAY_TASK_COUNT", count)));
        Assert.Equal((new Shard(i, n), "Slurm"), r);
    }

    [Fact]
    public void Slurm_count_alone_serves_when_max_is_absent()
    {
        var r = SchedulerEnvironment.Resolve(null,
            Env(("SLURM_ARRAY_TASK_ID", "5"), ("SLURM_ARRAY_TASK_MIN", "4"), ("SLURM_ARRAY_TASK_COUNT", "3")));
        Assert.Equal(new Shard(1, 3), r!.Value.Shard);
    }

    [Fact]
    public void An_irregular_Slurm_list_is_refused()
    {
        // sbatch --array=1,3,7: Slurm sets MIN 1, MAX 7, STEP 1, COUNT 3.
        var e = Assert.Throws<InputException>(() => SchedulerEnvironment.Resolve(null, Env(("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_MIN", "1"), ("SLURM_ARRAY_TASK_MAX", "7"), ("SLURM_ARRAY_TASK_STEP", "1"),
                ("SLURM_ARRAY_TASK_COUNT", "3"))));
        Assert.Contains("regular array", e.Message);
    }

    [Fact]
    public void Kubernetes_index_needs_the_count_from_the_command_line()
    {
        Assert.Equal((new Shard(2, 4), "Kubernetes"), SchedulerEnvironment.Resolve(4, Env(("JOB_COMPLETION_INDEX", "2"))));
        var e = Assert.Throws<InputException>(() => SchedulerEnvironment.Resolve(null, Env(("JOB_COMPLETION_INDEX", "2"))));
        Assert.Contains("--shards N", e.Message);
        Assert.Throws<InputException>(() => SchedulerEnvironment.Resolve(2, Env(("JOB_COMPLETION_INDEX", "2"))));
    }

    [Fact]
    public void Aws_batch_index_with_its_array_size()
    {
        Assert.Equal((new Shard(7, 16), "AWS Batch"),
            SchedulerEnvironment.Resolve(null, Env(("AWS_BATCH_JOB_ARRAY_INDEX", "7"), ("AWS_BATCH_JOB_ARRAY_SIZE", "16"))));
        Assert.Equal(new Shard(1, 2), SchedulerEnvironment.Resolve(2, Env(("AWS_BATCH_JOB_ARRAY_INDEX", "1")))!.Value.Shard);
        Assert.Throws<InputException>(() =>
            SchedulerEnvironment.Resolve(8, Env(("AWS_BATCH_JOB_ARRAY_INDEX", "1"), ("AWS_BATCH_JOB_ARRAY_SIZE", "16"))));
    }

    [Fact]
    public void No_scheduler_variable_means_no_shard() => Assert.Null(SchedulerEnvironment.Resolve(4, Env()));

    /// <summary>Issue 42: a huge task id was "not a whole number"; a task beyond the image's strips was blamed on --shard.</summary>
    [Theory]
    [InlineData("SLURM_ARRAY_TASK_ID", "99999999999")]
    [InlineData("SLURM_ARRAY_TASK_MAX", "-99999999999")]
    public void A_task_variable_beyond_the_whole_numbers_says_so_and_names_itself(string name, string value)
    {
        var env = name == "SLURM_ARRAY_TASK_ID" ? Env((name, value), ("SLURM_ARRAY_TASK_MAX", "3"))
            : Env(("SLURM_ARRAY_TASK_ID", "0"), (name, value));
        var e = Assert.Throws<InputException>(() => SchedulerEnvironment.Resolve(null, env));
        Assert.StartsWith($"{name}: '{value}' is beyond the ±2147483647", e.Message);
    }

    [Fact]
    public void A_job_array_task_beyond_the_images_strips_names_the_scheduler_not_shard()
    {
        var e = Assert.Throws<InputException>(() => new Shard(7, 10).Strip(8, 4, "Slurm job array task 7/10"));
        Assert.Equal("Slurm job array task 7/10: the 8×4 image has only 1 strip of 32 rows (hint: run an array of at most 1 task,"
            + " or a taller image)", e.Message);
        Assert.StartsWith("--shard 7/10: ", Assert.Throws<InputException>(() => new Shard(7, 10).Strip(8, 4)).Message);
    }

    [Fact]
    public void Sweep_slices_deal_every_job_to_exactly_one_shard()
    {
        for (int n = 1; n <= 5; n++)
            for (int job = 0; job < 23; job++)
                Assert.Equal(1, Enumerable.Range(0, n).Count(i => new Shard(i, n).Owns(job)));
    }
}
