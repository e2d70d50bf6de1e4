using System.Buffers.Binary;
using System.Numerics;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;

namespace SpectralRenderer.Scenes.Loading;

/// <summary>
/// Reads a density grid (<see cref="DensityGrid"/>) from Mitsuba's binary <c>.vol</c> format (Mitsuba 3,
/// src/render/volumegrid.cpp: "VOL", version byte 3, int32 encoding 1 = float32, int32 xres, yres, zres, int32 channels,
/// six float32 of a bounding box min xyz, max xyz, then xres·yres·zres·channels float32, x fastest, all little-endian) or
/// from a NumPy <c>.npy</c> array of float32 or float64 in C order with shape (nz, ny, nx) — indexed [z, y, x], so its last
/// axis is x, the same memory order. One channel (a density); every value finite and ≥ 0.
/// </summary>
public static class DensityGridReader
{
    /// <summary>The grid's samples and the .vol file's bounding box (null for .npy, which has none).</summary>
    public sealed record Samples(float[] Data, int Nx, int Ny, int Nz, (Vector3 Min, Vector3 Max)? Bounds);

    /// <summary>Reads <paramref name="bytes"/> as .npy when they start with NumPy's magic, else as .vol.</summary>
    public static Samples Read(byte[] bytes, string where) =>
        bytes.AsSpan().StartsWith(NpyWriter.Magic) ? ReadNpy(bytes, where) : ReadVol(bytes, where);

    const int VolHeader = 48;

    public static Samples ReadVol(byte[] b, string where)
    {
        const string Hint = "write it as Mitsuba's VolumeGrid.write does (\"VOL\", version 3, encoding 1 = float32)";
        if (b.Length < 4 || b[0] != 'V' || b[1] != 'O' || b[2] != 'L')
            throw new InputException($"{where}: byte 0", "not a .vol grid (no \"VOL\" magic) nor a .npy array", Hint);
        if (b[3] != 3) throw new InputException($"{where}: byte 3", $".vol version {b[3]} is not supported", Hint);
        if (b.Length < VolHeader)
            throw new InputException($"{where}: byte {b.Length}", $"the file is truncated in its {VolHeader}-byte header", Hint);
        int Int(int at) => BinaryPrimitives.ReadInt32LittleEndian(b.AsSpan(at));
        float Float(int at) => BinaryPrimitives.ReadSingleLittleEndian(b.AsSpan(at));
        int encoding = Int(4);
        if (encoding != 1)
            throw new InputException($"{where}: byte 4", $"encoding {encoding} is not supported", "only 1 (float32) is; " + Hint);
        int nx = Int(8), ny = Int(12), nz = Int(16), channels = Int(20);
        if (nx < 1 || ny < 1 || nz < 1)
            throw new InputException($"{where}: byte 8", $"the resolution {nx} × {ny} × {nz} is not positive", Hint);
        if (channels != 1)
            throw new InputException($"{where}: byte 20", $"the grid has {channels} channels", "a density grid has 1 channel");
        var min = new Vector3(Float(24), Float(28), Float(32));
        var max = new Vector3(Float(36), Float(40), Float(44));
        CheckBounds(min, max, $"{where}: byte 24");
        long count = (long)nx * ny * nz;
        if (count * 4 != b.Length - VolHeader)
            throw new InputException($"{where}: byte {VolHeader}",
                $"the header declares {nx} × {ny} × {nz} = {count} float32 values ({count * 4} bytes), the file holds "
                    + $"{b.Length - VolHeader} bytes of data", "the file is truncated or its header is wrong: write it again");
        var data = new float[count];
        for (long i = 0; i < count; i++) data[i] = BinaryPrimitives.ReadSingleLittleEndian(b.AsSpan((int)(VolHeader + 4 * i)));
        CheckValues(data, nx, ny, where);
        return new Samples(data, nx, ny, nz, (min, max));
    }

    public static Samples ReadNpy(byte[] bytes, string where)
    {
        var (shape, data) = NpyReader.Read(new MemoryStream(bytes), where);
        if (shape.Length != 3 || shape.Any(n => n < 1))
            throw new InputException($"{where}: header", $"the array's shape is ({string.Join(", ", shape)})",
                "a density grid is a 3-D array of shape (nz, ny, nx), indexed [z, y, x]");
        CheckValues(data, shape[2], shape[1], where);
        return new Samples(data, shape[2], shape[1], shape[0], null);
    }

    /// <summary>A box's corners: finite, min &lt; max on every axis.</summary>
    public static void CheckBounds(Vector3 min, Vector3 max, string where)
    {
        bool finite = float.IsFinite(min.X + min.Y + min.Z + max.X + max.Y + max.Z);
        if (!finite || !(min.X < max.X && min.Y < max.Y && min.Z < max.Z))
            throw new InputException(where, $"the grid's bounds {min} – {max} are {(finite ? "empty" : "not finite")}",
                "give a box's min and max corners, min < max on every axis, in scene units");
    }

    static void CheckValues(float[] data, int nx, int ny, string where)
    {
        for (int i = 0; i < data.Length; i++)
            if (!(data[i] >= 0 && float.IsFinite(data[i])))
                throw new InputException($"{where}: sample (x {i % nx}, y {i / nx % ny}, z {i / nx / ny})",
                    $"the density {data[i]} is {(float.IsFinite(data[i]) ? "negative" : "not finite")}",
                    "densities are finite and ≥ 0 (they scale the medium's coefficients)");
    }
}
