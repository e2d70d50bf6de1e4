using System.Text;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Geometry;

/// <summary>The storage format a PLY file declares in its header.</summary>
enum PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian }

/// <summary>The PLY scalar types (with their sized aliases, e.g. uchar = uint8).</summary>
enum PlyType : byte { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 }

/// <summary>A property of a PLY element: a scalar, or a list with a count type and an item type.</summary>
sealed record PlyProperty(string Name, PlyType Type, bool IsList, PlyType CountType);

/// <summary>A PLY element (vertex, face, tristrips, ...): how many instances and the properties of each.</summary>
sealed record PlyElement(string Name, int Count, List<PlyProperty> Properties, int HeaderLine)
{
    public int IndexOf(string name)
    {
        for (int i = 0; i < Properties.Count; i++)
            if (Properties[i].Name == name) return i;
        return -1;
    }

    /// <summary>Bytes per instance in a binary file, or -1 when a list makes it vary.</summary>
    public int FixedSize
    {
        get
        {
            int size = 0;
            foreach (var p in Properties)
            {
                if (p.IsList) return -1;
                size += PlyHeader.SizeOf(p.Type);
            }
            return size;
        }
    }
}

/// <summary>
/// The header of a PLY file (Turk 1994; the format as documented by Paul Bourke): "ply", "format", "comment",
/// "obj_info", "element NAME COUNT", "property TYPE NAME", "property list COUNTTYPE TYPE NAME", "end_header".
/// </summary>
sealed class PlyHeader
{
    public PlyFormat Format { get; private init; }
    public List<PlyElement> Elements { get; } = [];
    /// <summary>Byte offset of the first byte after "end_header\n".</summary>
    public int DataStart { get; private init; }

    public static int SizeOf(PlyType t) => t switch
    {
        PlyType.Int8 or PlyType.UInt8 => 1,
        PlyType.Int16 or PlyType.UInt16 => 2,
        PlyType.Int32 or PlyType.UInt32 or PlyType.Float32 => 4,
        _ => 8,
    };

    public static bool IsInteger(PlyType t) => t < PlyType.Float32;

    static readonly string[] TypeNames =
        ["char", "uchar", "short", "ushort", "int", "uint", "float", "double",
         "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"];

    static bool TryParseType(string name, out PlyType type)
    {
        int i = Array.IndexOf(TypeNames, name);
        type = (PlyType)(i % 8);
        return i >= 0;
    }

    public static PlyHeader Parse(ReadOnlySpan<byte> data, string path)
    {
        if (!data.StartsWith("ply"u8))
            throw new InputException($"{path}:1", "not a PLY file (it must start with 'ply')",
                "is this a PLY mesh? OBJ meshes need the .obj extension");
        PlyFormat? format = null;
        var elements = new List<PlyElement>();
        int pos = 0, lineNumber = 0;
        while (true)
        {
            lineNumber++;
            int eol = data[pos..].IndexOf((byte)'\n');
            if (eol < 0)
                throw new InputException($"{path}:{lineNumber}", "the header has no 'end_header' line (truncated file?)",
                    "the file may be truncated: export the mesh again");
            string line = Encoding.ASCII.GetString(data.Slice(pos, eol)).Trim();
            pos += eol + 1;
            string where = $"{path}:{lineNumber}";
            var words = line.Split((char[]?)null, StringSplitOptions.RemoveEmptyEntries);
            if (words.Length == 0) continue;
            switch (words[0])
            {
                case "ply" when lineNumber == 1:
                case "comment":
                case "obj_info":
                    break;
                case "format":
                    format = words.Length >= 2 ? words[1] switch
                    {
                        "ascii" => PlyFormat.Ascii,
                        "binary_little_endian" => PlyFormat.BinaryLittleEndian,
                        "binary_big_endian" => PlyFormat.BinaryBigEndian,
                        _ => null,
                    } : null;
                    if (format is null)
                        throw new InputException(where, $"unknown format '{(words.Length >= 2 ? words[1] : "")}'",
                            "ascii, binary_little_endian or binary_big_endian");
                    break;
                case "element":
                    if (words.Length != 3 || !int.TryParse(words[2], out int count) || count < 0)
                        throw new InputException(where, $"malformed element line {MessageText.Quote(line)}", "element NAME COUNT");
                    elements.Add(new PlyElement(words[1], count, [], lineNumber));
                    break;
                case "property":
                    if (elements.Count == 0)
                        throw new InputException(where, "property before any element",
                            "declare 'element NAME COUNT' before its 'property' lines");
                    elements[^1].Properties.Add(ParseProperty(words, line, where));
                    break;
                case "end_header":
                    if (format is null)
                        throw new InputException(where, "the header has no 'format' line",
                            "add 'format ascii 1.0' (or binary_little_endian/binary_big_endian) after 'ply'");
                    var header = new PlyHeader { Format = format.Value, DataStart = pos };
                    header.Elements.AddRange(elements);
                    return header;
                default:
                    throw new InputException(where, $"unknown header keyword {MessageText.Quote(words[0])}",
                        "header lines are ply, format, comment, obj_info, element, property and end_header");
            }
        }
    }

    static PlyProperty ParseProperty(string[] words, string line, string where)
    {
        bool isList = words.Length >= 2 && words[1] == "list";
        if (words.Length != (isList ? 5 : 3))
            throw new InputException(where, $"malformed property line {MessageText.Quote(line)}",
                "property TYPE NAME or property list COUNTTYPE TYPE NAME");
        var typeWords = isList ? words[2..4] : words[1..2];
        var types = new PlyType[typeWords.Length];
        for (int i = 0; i < typeWords.Length; i++)
            if (!TryParseType(typeWords[i], out types[i]))
                throw new InputException(where, $"unknown property type '{typeWords[i]}'", string.Join(" ", TypeNames));
        if (isList && !IsInteger(types[0]))
            throw new InputException(where, $"list count type '{typeWords[0]}' is not an integer type",
                "a list count is char, uchar, short, ushort, int or uint");
        return isList ? new PlyProperty(words[4], types[1], true, types[0]) : new PlyProperty(words[2], types[0], false, default);
    }
}
