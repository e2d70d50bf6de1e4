using System.Globalization;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Rendering;

namespace SpectralRenderer.Distributed;

/// <summary>
/// Shard <see cref="Index"/> of <see cref="Count"/> (0-based, as Slurm, Kubernetes and AWS Batch number array tasks).
/// A shard of a render is a horizontal strip of whole rows (<see cref="Strip(int, int)"/>); a shard of a sweep is every
/// Count-th job starting at Index.
/// </summary>
public readonly record struct Shard(int Index, int Count)
{
    /// <summary>
    /// Strip boundaries fall on multiples of this many rows: the renderer's tile rows (<see cref="Renderer.TileSize"/>),
    /// so a shard renders whole tiles in the same order as the whole render, and a multiple of the 16 scanlines of an
    /// OpenEXR ZIP chunk (1 for NO_COMPRESSION), so every chunk of a shard's EXR is a chunk of the whole image's.
    /// </summary>
    public const int RowAlignment = Renderer.TileSize;

    static Shard() { System.Diagnostics.Debug.Assert(RowAlignment % 16 == 0); }

    /// <summary>Parses "I/N" with 0 ≤ I &lt; N.</summary>
    public static Shard Parse(string text, string where = "--shard")
    {
        int slash = text.IndexOf('/');
        if (slash < 0 || !int.TryParse(text[..slash], NumberStyles.None, CultureInfo.InvariantCulture, out int i)
            || !int.TryParse(text[(slash + 1)..], NumberStyles.None, CultureInfo.InvariantCulture, out int n))
            throw new InputException(where, $"'{text}' is not I/N", "e.g. --shard 0/4 (the first of four shards; I counts from 0)");
        return Checked(i, n, where);
    }

    public static Shard Checked(int index, int count, string where)
    {
        if (count < 1) throw new InputException(where, $"shard count {count} is not at least 1", "give --shard I/N with N ≥ 1");
        if (index < 0 || index >= count)
            throw new InputException(where, $"shard index {index} is not in 0…{count - 1}", "shards count from 0");
        return new Shard(index, count);
    }

    /// <summary>
    /// The rows of this shard: the image's R = ⌈height / <see cref="RowAlignment"/>⌉ tile rows are dealt out in
    /// contiguous runs, shard i taking tile rows ⌊i·R/N⌋ … ⌊(i+1)·R/N⌋ − 1 (full width; the last strip ends at the
    /// image's last row). Every row belongs to exactly one shard.
    /// </summary>
    public PixelRect Strip(int width, int height) => Strip(width, height, null);

    /// <inheritdoc cref="Strip(int, int)"/>
    /// <param name="source">Where the shard came from, for an error (a job array's task); null: --shard.</param>
    public PixelRect Strip(int width, int height, string? source)
    {
        int rows = (height + RowAlignment - 1) / RowAlignment;
        if (Count > rows)
            throw new InputException(source ?? $"--shard {this}",
                $"the {width}×{height} image has only {rows} strip{(rows == 1 ? "" : "s")} of {RowAlignment} rows",
                source is null ? $"use at most {rows} shard{(rows == 1 ? "" : "s")}"
                    : $"run an array of at most {rows} task{(rows == 1 ? "" : "s")}, or a taller image");
        int t0 = (int)((long)Index * rows / Count), t1 = (int)((long)(Index + 1) * rows / Count);
        return new PixelRect(0, t0 * RowAlignment, width, Math.Min(height, t1 * RowAlignment));
    }

    /// <summary>Whether job <paramref name="job"/> of a sweep belongs to this shard (round robin: job mod N = I).</summary>
    public bool Owns(int job) => job % Count == Index;

    public override string ToString() => string.Create(CultureInfo.InvariantCulture, $"{Index}/{Count}");
}
