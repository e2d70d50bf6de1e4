using System.Globalization;
using System.Runtime.InteropServices;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Spectra;

/// <summary>
/// <see cref="LargeArrays"/>: the kernel's own accounting (/proc/self/smaps, AnonHugePages of the mapping that holds the
/// array) says a large array is backed by transparent huge pages once touched, where the kernel offers them on request.
/// </summary>
public class LargeArraysTests
{
    static string? ThpMode()
    {
        const string path = "/sys/kernel/mm/transparent_hugepage/enabled";
        if (!File.Exists(path)) return null;
        var text = File.ReadAllText(path);
        int a = text.IndexOf('['), b = text.IndexOf(']');
        return a >= 0 && b > a ? text[(a + 1)..b] : null;
    }

    /// <summary>The AnonHugePages (kB) of the mapping of /proc/self/smaps that contains <paramref name="address"/>.</summary>
    static long AnonHugePagesKb(ulong address)
    {
        bool inside = false;
        foreach (var line in File.ReadLines("/proc/self/smaps"))
        {
            int dash = line.IndexOf('-'), space = line.IndexOf(' ');
            if (dash > 0 && space > dash
                && ulong.TryParse(line.AsSpan(0, dash), NumberStyles.HexNumber, CultureInfo.InvariantCulture, out ulong lo)
                && ulong.TryParse(line.AsSpan(dash + 1, space - dash - 1), NumberStyles.HexNumber, CultureInfo.InvariantCulture,
                    out ulong hi))
            {
                inside = lo <= address && address < hi;
                continue;
            }
            if (inside && line.StartsWith("AnonHugePages:", StringComparison.Ordinal))
                return long.Parse(line["AnonHugePages:".Length..].Replace("kB", "").Trim(), CultureInfo.InvariantCulture);
        }
        return -1;
    }

    [SkippableFact]
    public void A_large_array_is_backed_by_huge_pages_once_touched()
    {
        Skip.IfNot(OperatingSystem.IsLinux(), "transparent huge pages are Linux's");
        var mode = ThpMode();
        Skip.If(mode is null or "never", $"transparent huge pages are off here ({mode ?? "no /sys/kernel/mm/transparent_hugepage"})");
        const int length = 16 << 20;   // 64 MiB of floats
        var a = LargeArrays.Uninitialized<float>(length);
        Assert.Equal(length, a.Length);
        for (int i = 0; i < a.Length; i += 1024) a[i] = i;   // touch every page
        ulong start = (ulong)Marshal.UnsafeAddrOfPinnedArrayElement(a, 0);   // on the pinned heap: it does not move
        ulong probe = (start + (2 << 20) - 1) & ~((ulong)(2 << 20) - 1);   // the first whole 2 MiB extent
        long kb = AnonHugePagesKb(probe);
        Assert.True(kb > 0, $"the array's mapping has AnonHugePages {kb} kB (THP mode {mode})");
        for (int i = 0; i < a.Length; i += 1024) Assert.Equal(i, a[i]);
        GC.KeepAlive(a);
    }

    [Fact]
    public void Small_arrays_are_plain_uninitialised_arrays_of_the_length_asked()
    {
        var a = LargeArrays.Uninitialized<int>(1000);
        Assert.Equal(1000, a.Length);
        a.AsSpan().Fill(7);
        Assert.All(a, v => Assert.Equal(7, v));
        Assert.Empty(LargeArrays.Uninitialized<byte>(0));
    }
}
