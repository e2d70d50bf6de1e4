using System.Buffers.Binary;
using System.Globalization;
using System.Runtime.CompilerServices;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Geometry;

/// <summary>
/// Reads PLY body values one at a time from the file's bytes, in any of the three formats, and knows which
/// element instance it is in so errors can say "element 'face' #12 at byte 345". The reader uses it for ascii
/// files, and for the binary elements its bulk path does not take (lists in the vertex element, truncated data).
/// </summary>
ref struct PlyCursor(ReadOnlySpan<byte> data, int start, PlyFormat format, string path)
{
    readonly ReadOnlySpan<byte> _data = data;
    readonly PlyFormat _format = format;
    readonly string _path = path;
    int _pos = start;
    int _valueStart = start;

    public string Element = "";
    public int Instance;

    public readonly int Position => _pos;
    public readonly int Remaining => _data.Length - _pos;

    public InputException Error(string what, string hint) => Error(_path, Element, Instance, _valueStart, what, hint);

    /// <summary>"file: element 'face' #12 at byte 345: what".</summary>
    public static InputException Error(string path, string element, int instance, int at, string what, string hint) =>
        new($"{path}: element '{element}' #{instance} at byte {at}", what, hint);

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public double ReadReal(PlyType type)
    {
        if (_format == PlyFormat.Ascii)
        {
            var token = NextToken();
            if (!double.TryParse(token, NumberStyles.Float, CultureInfo.InvariantCulture, out double v))
                throw Error($"{MessageText.Quote(token)} is not a number", "ASCII PLY values are plain numbers separated by spaces");
            return v;
        }
        return DecodeReal(type, Take(PlyHeader.SizeOf(type)), _format == PlyFormat.BinaryLittleEndian);
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public long ReadInteger(PlyType type)
    {
        if (_format == PlyFormat.Ascii)
        {
            var token = NextToken();
            if (long.TryParse(token, NumberStyles.AllowLeadingSign, CultureInfo.InvariantCulture, out long i)) return i;
            // Some writers print integral values as reals ("3.0").
            if (double.TryParse(token, NumberStyles.Float, CultureInfo.InvariantCulture, out double d) && d == Math.Floor(d)
                && Math.Abs(d) < 1e15)
                return (long)d;
            throw Error($"{MessageText.Quote(token)} is not an integer", "list counts and indices are whole numbers");
        }
        var bytes = Take(PlyHeader.SizeOf(type));
        bool le = _format == PlyFormat.BinaryLittleEndian;
        if (!PlyHeader.IsInteger(type))
        {
            double d = type == PlyType.Float32
                ? (le ? BinaryPrimitives.ReadSingleLittleEndian(bytes) : BinaryPrimitives.ReadSingleBigEndian(bytes))
                : (le ? BinaryPrimitives.ReadDoubleLittleEndian(bytes) : BinaryPrimitives.ReadDoubleBigEndian(bytes));
            if (d != Math.Floor(d) || Math.Abs(d) >= 1e15)
                throw Error($"{d} is not an integer", "list counts and indices are whole numbers");
            return (long)d;
        }
        return DecodeInteger(type, bytes, le);
    }

    /// <summary>A binary value of any type at the start of <paramref name="b"/>, as a real.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static double DecodeReal(PlyType type, ReadOnlySpan<byte> b, bool le) => type switch
    {
        PlyType.Float32 => le ? BinaryPrimitives.ReadSingleLittleEndian(b) : BinaryPrimitives.ReadSingleBigEndian(b),
        PlyType.Float64 => le ? BinaryPrimitives.ReadDoubleLittleEndian(b) : BinaryPrimitives.ReadDoubleBigEndian(b),
        _ => DecodeInteger(type, b, le),
    };

    /// <summary>A binary value of an integer type at the start of <paramref name="b"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static long DecodeInteger(PlyType type, ReadOnlySpan<byte> b, bool le) => type switch
    {
        PlyType.Int8 => (sbyte)b[0],
        PlyType.UInt8 => b[0],
        PlyType.Int16 => le ? BinaryPrimitives.ReadInt16LittleEndian(b) : BinaryPrimitives.ReadInt16BigEndian(b),
        PlyType.UInt16 => le ? BinaryPrimitives.ReadUInt16LittleEndian(b) : BinaryPrimitives.ReadUInt16BigEndian(b),
        PlyType.Int32 => le ? BinaryPrimitives.ReadInt32LittleEndian(b) : BinaryPrimitives.ReadInt32BigEndian(b),
        _ => le ? BinaryPrimitives.ReadUInt32LittleEndian(b) : BinaryPrimitives.ReadUInt32BigEndian(b),
    };

    /// <summary>Skips one property value (a scalar, or a list with its items).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public void Skip(PlyProperty p)
    {
        if (!p.IsList) { SkipValue(p.Type); return; }
        long n = ReadCount(p);
        if (_format != PlyFormat.Ascii) { Take(checked((int)Math.Min(n * PlyHeader.SizeOf(p.Type), int.MaxValue))); return; }
        for (long i = 0; i < n; i++) SkipValue(p.Type);
    }

    /// <summary>A list's item count, checked non-negative.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public long ReadCount(PlyProperty list)
    {
        long n = ReadInteger(list.CountType);
        if (n < 0) throw Error($"list '{list.Name}' has negative length {n}", "the file is corrupt at this place: export the mesh again");
        return n;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void SkipValue(PlyType type)
    {
        if (_format == PlyFormat.Ascii) NextToken();
        else Take(PlyHeader.SizeOf(type));
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    ReadOnlySpan<byte> Take(int size)
    {
        _valueStart = _pos;
        if (_data.Length - _pos < size)
            throw Error($"unexpected end of file (truncated data: needs {size} more bytes, {_data.Length - _pos} left)",
                "the file was cut short or its header's counts are wrong: export the mesh again");
        var bytes = _data.Slice(_pos, size);
        _pos += size;
        return bytes;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    ReadOnlySpan<byte> NextToken()
    {
        int i = _pos;
        while (i < _data.Length && IsSpace(_data[i])) i++;
        _valueStart = i;
        int start = i;
        while (i < _data.Length && !IsSpace(_data[i])) i++;
        _pos = i;
        if (start == i)
            throw Error("unexpected end of file (truncated data)",
                "the file was cut short or its header's counts are wrong: export the mesh again");
        return _data[start..i];
    }

    static bool IsSpace(byte b) => b is (byte)' ' or (byte)'\t' or (byte)'\n' or (byte)'\r' or (byte)'\v' or (byte)'\f';
}
