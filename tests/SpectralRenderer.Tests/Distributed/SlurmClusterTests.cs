using System.Diagnostics;

namespace SpectralRenderer.Tests.Distributed;

/// <summary>
/// tests/slurm/ci.sh on a one-node Slurm (slurm-wlm + munge, installed by .ci/run): 4-task arrays render the shards of
/// the glass/mirror scene (and the §3.2 bunny with SPECTRAL_MODELS) and run a sweep; the merge must equal the
/// single-process render byte for byte. At 128² (SHARD_SIZE) to keep CI short; the 1024² bar runs locally (BENCHMARKS.md).
/// </summary>
[Collection("Alone")]
[Trait("Category", "Slurm")]
[Trait("Category", "Interop")]   // a real cluster: not part of the fast core (README)
public class SlurmClusterTests
{
    [SkippableFact]
    public void Shard_and_sweep_arrays_through_a_real_Slurm_merge_to_the_single_render()
    {
        Skip.IfNot(OperatingSystem.IsLinux(), "the one-node Slurm cluster needs Linux");
        foreach (var tool in new[] { "/usr/bin/sbatch", "/usr/sbin/slurmctld", "/usr/sbin/slurmd", "/usr/sbin/munged" })
            Skip.IfNot(File.Exists(tool),
                $"Slurm is not installed ({tool} is missing): .ci/run installs Debian's slurm-wlm and munge as root");
        Skip.IfNot(File.Exists("/usr/bin/python3"), "tests/slurm/ci.sh compares the manifests with python3, which is not installed");
        Skip.IfNot(Environment.UserName == "root", "the one-node Slurm cluster runs slurmd and munged as root");
        Skip.If(Environment.GetEnvironmentVariable("SLURM_JOB_ID") is not null, "already inside a Slurm job: a second cluster would clash");
        var repo = Path.GetFullPath(Path.Combine(AppContext.BaseDirectory, "../../../../.."));
        var psi =
            new ProcessStartInfo("/bin/bash") { RedirectStandardOutput = true, RedirectStandardError = true, UseShellExecute = false };
        foreach (var a in new[] { Path.Combine(repo, "tests/slurm/ci.sh"), Path.Combine(AppContext.BaseDirectory, "spectral.dll"),
            Path.Combine(Reference.TempDir(), "slurm") })
            psi.ArgumentList.Add(a);
        using var p = Process.Start(psi)!;
        var output = p.StandardOutput.ReadToEndAsync();
        var errors = p.StandardError.ReadToEndAsync();
        if (!p.WaitForExit(600_000)) { p.Kill(entireProcessTree: true); Assert.Fail("tests/slurm/ci.sh did not finish in 10 minutes"); }
        Assert.True(p.ExitCode == 0, $"tests/slurm/ci.sh exited {p.ExitCode}:\n{output.Result}\n{errors.Result}");
        Assert.Contains("4 shards of glass-mirror", output.Result);
        Assert.Contains("rendered no job twice", output.Result);
    }
}
