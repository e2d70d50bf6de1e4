using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;

namespace SpectralRenderer.Spectra;

/// <summary>
/// The arrays a render fills once, whole (the framebuffer, the band planes of the writers): uninitialised, and on Linux
/// advised to transparent huge pages (madvise(2) MADV_HUGEPAGE) before anything touches them, so the kernel backs them
/// with 2 MiB pages — one page fault per 2 MiB instead of per 4 KiB. A 401-band cube at 512² is 420 MB: 102,000 faults
/// in the render's threads with small pages (BENCHMARKS.md). Where the kernel does not do it (THP "never", another OS,
/// no libc) the array is the same, with small pages; its values never depend on it.
/// </summary>
public static partial class LargeArrays
{
    const nint HugePage = 2 << 20;

    /// <summary>Arrays from this size up are advised (smaller ones gain nothing from a few huge pages).</summary>
    public const long AdviseFromBytes = 4L * HugePage;

    /// <summary>An uninitialised array of <paramref name="length"/> elements, on huge pages where the kernel allows.</summary>
    public static T[] Uninitialized<T>(int length) where T : unmanaged
    {
        long bytes = (long)length * Unsafe.SizeOf<T>();
        if (bytes < AdviseFromBytes || !OperatingSystem.IsLinux()) return GC.AllocateUninitializedArray<T>(length);
        // On the pinned heap: the advised range stays the array's.
        var array = GC.AllocateUninitializedArray<T>(length, pinned: true);
        Advise(ref Unsafe.As<T, byte>(ref MemoryMarshal.GetArrayDataReference(array)), bytes);
        return array;
    }

    static unsafe void Advise(ref byte first, long bytes)
    {
        nint start = (nint)Unsafe.AsPointer(ref first);
        // The whole 2 MiB extents inside the array (madvise takes page-aligned ranges; only whole extents can be huge).
        nint lo = (start + HugePage - 1) & ~(HugePage - 1), hi = (start + (nint)bytes) & ~(HugePage - 1);
        if (hi <= lo) return;
        try { _ = Madvise(lo, (nuint)(hi - lo), MadvHugePage); }
        catch (Exception e) when (e is DllNotFoundException or EntryPointNotFoundException) { }
    }

    const int MadvHugePage = 14;   // <sys/mman.h>, Linux

    // glibc's soname: the C library the process has loaded already (a musl system has none, and keeps small pages).
    [LibraryImport("libc.so.6", EntryPoint = "madvise")]
    private static partial int Madvise(nint address, nuint length, int advice);
}
