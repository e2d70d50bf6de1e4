using System.Buffers.Binary;
using System.Numerics;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Imaging;

/// <summary>A decoded JPEG: 8-bit samples row by row from the top, 1 (grey) or 3 (R, G, B) per pixel.</summary>
public sealed record JpegImage(int Width, int Height, int Channels, byte[] Samples);

/// <summary>
/// A baseline JPEG decoder (ITU-T T.81 / ISO 10918-1): sequential DCT with Huffman coding and 8-bit samples (SOF0, and
/// SOF1 with 8-bit samples, the same process), interleaved or one component per scan, any integral sampling factors
/// (4:4:4, 4:2:2, 4:2:0, 4:4:0), restart intervals; one component is grey, three are YCbCr (JFIF, converted to RGB by
/// T.871 §7) unless an Adobe APP14 marker says transform 0 or the components are named 'R', 'G', 'B'. The arithmetic is
/// the one of the Independent JPEG Group's "islow" decoder, so the result equals <c>djpeg -dct int -nosmooth</c>: the
/// 8×8 inverse DCT of Loeffler, Ligtenberg and Moschytz (1989) in 32-bit fixed point (13 fraction bits for the
/// constants, 2 extra bits between the passes), the YCbCr→RGB products in 16-bit fixed point rounded once, and
/// subsampled chroma replicated over the pixels it covers (box upsampling; djpeg's default "fancy" triangle filter is
/// what <c>-nosmooth</c> turns off). Progressive, lossless, hierarchical, arithmetic-coded and 12-bit files are refused
/// in one line, as are CMYK (four components) and anything malformed.
/// </summary>
public static class JpegReader
{
    public static JpegImage Read(string path) => Read(InputFile.ReadAllBytes(path, "JPEG file"), path);

    public static JpegImage Read(byte[] bytes, string where = "JPEG") => new Decoder(bytes, where).Decode();

    /// <summary>Does the file start as a JPEG does (SOI, then a marker)?</summary>
    public static bool IsJpeg(ReadOnlySpan<byte> head) => head.Length >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF;

    sealed class Component
    {
        public int Id, H, V, QuantTable, DcTable, AcTable, Predictor;
        public int BlocksPerLine, BlocksPerColumn;   // the plane's blocks: whole MCUs
        public int Width, Height;                    // the component's own size, ceil(X·H/Hmax) × ceil(Y·V/Vmax)
        public byte[] Plane = [];
    }

    /// <summary>A Huffman table (T.81 Annex C): codes by length, with a 9-bit look-up of the short ones.</summary>
    sealed class HuffmanTable
    {
        public const int LookupBits = 9;
        public readonly int[] MaxCode = new int[18];   // the largest code of each length, −1 when none; [17] a sentinel
        public readonly int[] ValueOffset = new int[17];
        public readonly byte[] Values;
        public readonly ushort[] Lookup = new ushort[1 << LookupBits];   // (length << 8) | value, 0 when longer

        public HuffmanTable(ReadOnlySpan<byte> counts, byte[] values, Func<string, InputException> error)
        {
            Values = values;
            int code = 0, k = 0;
            for (int length = 1; length <= 16; length++)
            {
                int n = counts[length - 1];
                ValueOffset[length] = k - code;
                code += n;
                k += n;
                // Codes of a length must fit in it, and none may be all ones (T.81 C.2; a prefix of the fill bits).
                if (code >= 1 << length) throw error($"the Huffman table has more codes of length {length} than fit in {length} bits");
                MaxCode[length] = n > 0 ? code - 1 : -1;
                if (length <= LookupBits)
                    for (int c = code - n; c < code; c++)
                    {
                        int shift = LookupBits - length, value = Values[ValueOffset[length] + c];
                        for (int fill = 0; fill < 1 << shift; fill++) Lookup[(c << shift) | fill] = (ushort)((length << 8) | value);
                    }
                code <<= 1;
            }
            MaxCode[17] = int.MaxValue;
        }
    }

    sealed class Decoder(byte[] data, string where)
    {
        readonly int[][] _quant = new int[4][];
        readonly HuffmanTable?[] _dc = new HuffmanTable?[4], _ac = new HuffmanTable?[4];
        Component[] _components = [];
        int _width, _height, _hMax, _vMax, _mcusPerLine, _mcusPerColumn, _restartInterval;
        bool _adobeRgb, _frameSeen;
        int _pos;

        // The entropy-coded bit stream (T.81 F.2.2.5): bits arrive MSB first in a 64-bit buffer; a stuffed 0xFF 0x00 is one
        // 0xFF byte; at a marker the stream ends and zeros are shifted in, but using them is an error (a truncated scan).
        ulong _bits;
        int _bitCount, _realBits;
        bool _atMarker;

        InputException Error(string what, string hint) => new($"{where}: byte {_pos}", what, hint);

        InputException Broken(string what) => Error(what, "the file is damaged or not a baseline JPEG: save it again");

        public JpegImage Decode()
        {
            if (data.Length < 4 || data[0] != 0xFF || data[1] != 0xD8)
                throw new InputException($"{where}: byte 0", "not a JPEG file (no SOI marker FF D8)",
                    "is this a JPEG image? it must start with FF D8");
            _pos = 2;
            bool scanned = false;
            while (true)
            {
                int marker = NextMarker();
                if (marker == 0xD9) break;   // EOI
                if (marker is >= 0xD0 and <= 0xD7) throw Broken($"restart marker RST{marker - 0xD0} outside a scan");
                if (marker == 0x01) continue;   // TEM, no length
                int length = Segment();
                int end = _pos + length - 2;
                switch (marker)
                {
                    case 0xC0 or 0xC1: Frame(end); break;
                    case 0xC2 or 0xC6 or 0xCA or 0xCE:
                        throw Error("progressive JPEG is not supported", "save it as a baseline (sequential) JPEG");
                    case 0xC3 or 0xC5 or 0xC7 or 0xCB or 0xCD or 0xCF:
                        throw Error($"{(marker is 0xC3 or 0xCB ? "lossless" : "hierarchical")} JPEG is not supported",
                            "save it as a baseline JPEG");
                    case 0xC9:
                        throw Error("arithmetic-coded JPEG is not supported", "save it as a baseline (Huffman-coded) JPEG");
                    case 0xC4: HuffmanTables(end); break;
                    case 0xCC: throw Error("arithmetic-coded JPEG is not supported", "save it as a baseline (Huffman-coded) JPEG");
                    case 0xDB: QuantTables(end); break;
                    case 0xDD:
                        if (length != 4) throw Broken("the DRI segment is not 4 bytes long");
                        _restartInterval = BinaryPrimitives.ReadUInt16BigEndian(data.AsSpan(_pos));
                        break;
                    case 0xDA:
                        Scan(end);
                        scanned = true;
                        continue;   // the scan left _pos after its entropy-coded data
                    case 0xDC: throw Error("a DNL marker (height given after the scan) is not supported", "save the JPEG again");
                    case 0xEE: Adobe(end); break;
                }
                _pos = end;
            }
            if (!scanned) throw Broken("the file has no image data (no SOS before EOI)");
            return Output();
        }

        /// <summary>The next marker's code, skipping fill bytes 0xFF; anything else between segments is an error.</summary>
        int NextMarker()
        {
            if (_pos >= data.Length) throw Error("the file ends before its EOI marker", "the file is truncated: save it again");
            if (data[_pos] != 0xFF) throw Broken($"expected a marker, found byte 0x{data[_pos]:X2}");
            while (_pos < data.Length && data[_pos] == 0xFF) _pos++;
            if (_pos >= data.Length) throw Error("the file ends before its EOI marker", "the file is truncated: save it again");
            if (data[_pos] == 0) throw Broken("a stuffed byte FF 00 outside a scan");
            return data[_pos++];
        }

        /// <summary>The segment's length field (it counts itself), checked against the file; _pos moves past it.</summary>
        int Segment()
        {
            if (_pos + 2 > data.Length) throw Error("the file ends inside a segment header", "the file is truncated: save it again");
            int length = BinaryPrimitives.ReadUInt16BigEndian(data.AsSpan(_pos));
            if (length < 2 || _pos + length > data.Length)
                throw Error($"a segment of {length} bytes runs past the end of the file", "the file is truncated: save it again");
            _pos += 2;
            return length;
        }

        void Frame(int end)
        {
            if (_frameSeen) throw Broken("a second frame header (SOF)");
            if (end - _pos < 6) throw Broken("the frame header (SOF) is too short");
            int precision = data[_pos];
            if (precision != 8)
                throw Error($"{precision}-bit JPEG is not supported", "save it with 8-bit samples (baseline)");
            _height = BinaryPrimitives.ReadUInt16BigEndian(data.AsSpan(_pos + 1));
            _width = BinaryPrimitives.ReadUInt16BigEndian(data.AsSpan(_pos + 3));
            int n = data[_pos + 5];
            if (_width == 0 || _height == 0) throw Error("the image has no pixels (or its height comes in a DNL marker)", "save it again");
            if (n is not (1 or 3))
                throw Error($"{n} colour components are not supported (CMYK?)", "save the image as greyscale or RGB/YCbCr");
            if (end - _pos != 6 + 3 * n) throw Broken("the frame header's length does not match its component count");
            _components = new Component[n];
            for (int i = 0; i < n; i++)
            {
                int at = _pos + 6 + 3 * i;
                var c = new Component { Id = data[at], H = data[at + 1] >> 4, V = data[at + 1] & 15, QuantTable = data[at + 2] };
                if (c.H is < 1 or > 4 || c.V is < 1 or > 4) throw Broken($"component {c.Id} has sampling factors {c.H}×{c.V}");
                if (c.QuantTable > 3) throw Broken($"component {c.Id} names quantisation table {c.QuantTable}");
                _components[i] = c;
            }
            _hMax = _components.Max(c => c.H);
            _vMax = _components.Max(c => c.V);
            foreach (var c in _components)
                if (_hMax % c.H != 0 || _vMax % c.V != 0)
                    throw Error($"component {c.Id}'s sampling {c.H}×{c.V} is not a whole fraction of {_hMax}×{_vMax}",
                        "save it with 4:4:4, 4:2:2 or 4:2:0 sampling");
            _mcusPerLine = (_width + 8 * _hMax - 1) / (8 * _hMax);
            _mcusPerColumn = (_height + 8 * _vMax - 1) / (8 * _vMax);
            // At least 2 bits code a block (a DC difference of 0 and an end of block), so the file bounds the samples.
            long samples = 0;
            foreach (var c in _components) samples += 64L * _mcusPerLine * c.H * _mcusPerColumn * c.V;
            if (samples > 256L * data.Length + (1 << 20) || samples > Array.MaxLength)
                throw Error($"the header declares {_width}×{_height} pixels, more than the file's {data.Length} bytes can code",
                    "the file is truncated or its header is damaged: save it again");
            foreach (var c in _components)
            {
                c.BlocksPerLine = _mcusPerLine * c.H;
                c.BlocksPerColumn = _mcusPerColumn * c.V;
                c.Width = (int)(((long)_width * c.H + _hMax - 1) / _hMax);
                c.Height = (int)(((long)_height * c.V + _vMax - 1) / _vMax);
                c.Plane = new byte[64L * c.BlocksPerLine * c.BlocksPerColumn];
            }
            _frameSeen = true;
        }

        void QuantTables(int end)
        {
            while (_pos < end)
            {
                int pq = data[_pos] >> 4, tq = data[_pos] & 15;
                if (pq > 1 || tq > 3) throw Broken($"quantisation table {tq} with precision {pq}");
                int size = pq == 0 ? 64 : 128;
                if (_pos + 1 + size > end) throw Broken("the DQT segment is shorter than its tables");
                var table = new int[64];
                for (int k = 0; k < 64; k++)
                    table[ZigZag[k]] = pq == 0 ? data[_pos + 1 + k] : BinaryPrimitives.ReadUInt16BigEndian(data.AsSpan(_pos + 1 + 2 * k));
                _quant[tq] = table;
                _pos += 1 + size;
            }
        }

        void HuffmanTables(int end)
        {
            while (_pos < end)
            {
                int tc = data[_pos] >> 4, th = data[_pos] & 15;
                if (tc > 1 || th > 3) throw Broken($"Huffman table class {tc}, number {th}");
                if (_pos + 17 > end) throw Broken("the DHT segment is shorter than its table");
                var counts = data.AsSpan(_pos + 1, 16);
                int total = 0;
                foreach (var count in counts) total += count;
                if (total > 256 || _pos + 17 + total > end) throw Broken("the DHT segment is shorter than its table");
                var values = data.AsSpan(_pos + 17, total).ToArray();
                var table = new HuffmanTable(counts, values, what => Broken(what));
                (tc == 0 ? _dc : _ac)[th] = table;
                _pos += 17 + total;
            }
        }

        void Adobe(int end)
        {
            // "Adobe" + version (2) + flags0 (2) + flags1 (2) + transform (1): 0 = RGB or CMYK untransformed, 1 = YCbCr.
            if (end - _pos >= 12 && data.AsSpan(_pos, 5).SequenceEqual("Adobe"u8)) _adobeRgb = data[_pos + 11] == 0;
        }

        void Scan(int end)
        {
            if (!_frameSeen) throw Broken("a scan (SOS) before the frame header (SOF)");
            if (end - _pos < 1) throw Broken("the scan header (SOS) is too short");
            int n = data[_pos];
            if (n < 1 || n > 4 || end - _pos != 4 + 2 * n) throw Broken("the scan header's length does not match its component count");
            var scan = new Component[n];
            int blocksPerMcu = 0;
            for (int i = 0; i < n; i++)
            {
                int id = data[_pos + 1 + 2 * i], tables = data[_pos + 2 + 2 * i];
                var c = Array.Find(_components, c => c.Id == id) ?? throw Broken($"the scan names component {id}, not in the frame");
                if (Array.IndexOf(scan, c) >= 0) throw Broken($"the scan names component {id} twice");
                c.DcTable = tables >> 4;
                c.AcTable = tables & 15;
                if (c.DcTable > 3 || c.AcTable > 3 || _dc[c.DcTable] is null || _ac[c.AcTable] is null)
                    throw Broken($"component {id}'s scan uses a Huffman table that was not defined");
                if (_quant[c.QuantTable] is null) throw Broken($"component {id}'s quantisation table was not defined");
                scan[i] = c;
                blocksPerMcu += c.H * c.V;
            }
            if (n > 1 && blocksPerMcu > 10) throw Broken($"an MCU of {blocksPerMcu} blocks (T.81 allows 10)");
            int ss = data[_pos + 1 + 2 * n], se = data[_pos + 2 + 2 * n], a = data[_pos + 3 + 2 * n];
            if (ss != 0 || se != 63 || a != 0)
                throw Error("a spectral-selection or successive-approximation scan (progressive JPEG) is not supported",
                    "save it as a baseline JPEG");
            _pos = end;
            DecodeScan(scan);
        }

        void DecodeScan(Component[] scan)
        {
            foreach (var c in scan) c.Predictor = 0;
            ResetBits();
            Span<int> block = stackalloc int[64];
            Span<int> workspace = stackalloc int[64];
            int mcusPerLine, mcus;
            if (scan.Length == 1)
            {
                // One component: its blocks in raster order over the component's own size (T.81 A.2.2).
                var c = scan[0];
                mcusPerLine = (c.Width + 7) / 8;
                mcus = mcusPerLine * ((c.Height + 7) / 8);
            }
            else
            {
                mcusPerLine = _mcusPerLine;
                mcus = _mcusPerLine * _mcusPerColumn;
            }
            int restart = 0;
            for (int m = 0; m < mcus; m++)
            {
                if (_restartInterval > 0 && m > 0 && m % _restartInterval == 0)
                {
                    ExpectRestart(restart);
                    restart = (restart + 1) & 7;
                    foreach (var c in scan) c.Predictor = 0;
                }
                int mx = m % mcusPerLine, my = m / mcusPerLine;
                foreach (var c in scan)
                {
                    int h = scan.Length == 1 ? 1 : c.H, v = scan.Length == 1 ? 1 : c.V;
                    for (int by = 0; by < v; by++)
                        for (int bx = 0; bx < h; bx++)
                        {
                            DecodeBlock(c, block);
                            int x = mx * h + bx, y = my * v + by;
                            InverseDct(block, workspace, c.Plane.AsSpan(y * 8 * c.BlocksPerLine * 8 + x * 8), c.BlocksPerLine * 8);
                        }
                }
            }
            EndScan();
        }

        /// <summary>One block's coefficients (T.81 F.2.2.1–F.2.2.2), dequantised, in natural order.</summary>
        void DecodeBlock(Component c, Span<int> block)
        {
            block.Clear();
            var quant = _quant[c.QuantTable];
            int s = DecodeHuffman(_dc[c.DcTable]!);
            if (s > 11) throw Broken($"a DC difference of category {s} (at most 11 for 8-bit samples)");
            int diff = s == 0 ? 0 : Extend(Receive(s), s);
            c.Predictor += diff;
            block[0] = c.Predictor * quant[0];
            var ac = _ac[c.AcTable]!;
            for (int k = 1; k < 64;)
            {
                int rs = DecodeHuffman(ac), r = rs >> 4;
                s = rs & 15;
                if (s == 0)
                {
                    if (r != 15) break;   // end of block
                    k += 16;              // ZRL: sixteen zeros
                    continue;
                }
                k += r;
                if (k > 63) throw Broken("a block's coefficients run past the 64th");
                if (s > 10) throw Broken($"an AC coefficient of category {s} (at most 10 for 8-bit samples)");
                int z = ZigZag[k++];
                block[z] = Extend(Receive(s), s) * quant[z];
            }
        }

        static int Extend(int v, int s) => v < 1 << (s - 1) ? v - (1 << s) + 1 : v;

        void ResetBits()
        {
            _bits = 0;
            _bitCount = _realBits = 0;
            _atMarker = false;
        }

        /// <summary>Fills the buffer to at least 57 bits: data bytes until a marker, zeros after it.</summary>
        void Fill()
        {
            while (_bitCount <= 56)
            {
                int b = 0;
                if (!_atMarker && _pos < data.Length)
                {
                    b = data[_pos];
                    if (b == 0xFF)
                    {
                        int next = _pos + 1;
                        while (next < data.Length && data[next] == 0xFF) next++;
                        if (next < data.Length && data[next] == 0) _pos = next + 1;
                        else { _atMarker = true; b = 0; _pos = next - 1; }   // _pos on the marker's last 0xFF
                    }
                    else _pos++;
                    if (!_atMarker) _realBits += 8;
                }
                else _atMarker = true;
                _bits |= (ulong)b << (56 - _bitCount);
                _bitCount += 8;
            }
        }

        void Consume(int n)
        {
            if (n > _realBits) throw Error("the image data ends before the last block", "the file is truncated: save it again");
            _bits <<= n;
            _bitCount -= n;
            _realBits -= n;
        }

        int Receive(int s)
        {
            if (_bitCount < s) Fill();
            int v = (int)(_bits >> (64 - s));
            Consume(s);
            return v;
        }

        int DecodeHuffman(HuffmanTable table)
        {
            if (_bitCount < 16) Fill();
            int entry = table.Lookup[(int)(_bits >> (64 - HuffmanTable.LookupBits))];
            if (entry != 0)
            {
                Consume(entry >> 8);
                return entry & 0xFF;
            }
            int length = HuffmanTable.LookupBits + 1;
            int code = (int)(_bits >> (64 - length));
            while (code > table.MaxCode[length])
            {
                length++;
                code = (int)(_bits >> (64 - length));
            }
            if (length > 16) throw Broken("a Huffman code that is not in its table");
            Consume(length);
            return table.Values[table.ValueOffset[length] + code];
        }

        /// <summary>The rest of the byte is padding; the next marker must be RSTn (T.81 F.1.2.3, E.2.4); predictors reset.</summary>
        void ExpectRestart(int n)
        {
            int marker = MarkerAfterData();
            if (marker != 0xD0 + n)
                throw Broken($"expected the restart marker RST{n}, found {(marker < 0 ? "the end of the file" : $"marker 0x{marker:X2}")}");
            _pos += 2;
            ResetBits();
        }

        /// <summary>After the scan's last MCU: the position of the marker that ends the entropy-coded data.</summary>
        void EndScan()
        {
            MarkerAfterData();
            ResetBits();
        }

        /// <summary>Moves _pos to the marker that follows the entropy-coded data consumed so far (bytes the buffer read ahead
        /// are data of the same segment, not used); returns the marker's code, or −1 at the end of the file.</summary>
        int MarkerAfterData()
        {
            while (!_atMarker && _pos < data.Length)
            {
                if (data[_pos] == 0xFF)
                {
                    int next = _pos + 1;
                    while (next < data.Length && data[next] == 0xFF) next++;
                    if (next < data.Length && data[next] == 0) { _pos = next + 1; continue; }
                    _pos = next - 1;
                    break;
                }
                _pos++;
            }
            if (_pos + 1 >= data.Length) return -1;
            int at = _pos + 1;
            while (at < data.Length && data[at] == 0xFF) at++;
            if (at >= data.Length) return -1;
            _pos = at - 1;
            return data[at];
        }

        /// <summary>Each component upsampled by replication to the image grid and converted to 8-bit RGB (or grey).</summary>
        JpegImage Output()
        {
            int channels = _components.Length == 1 ? 1 : 3;
            var samples = new byte[(long)_width * _height * channels];
            if (channels == 1)
            {
                var c = _components[0];
                int stride = c.BlocksPerLine * 8;
                for (int y = 0; y < _height; y++) c.Plane.AsSpan(y * stride, _width).CopyTo(samples.AsSpan(y * _width));
                return new JpegImage(_width, _height, 1, samples);
            }
            bool rgb = _adobeRgb || (_components[0].Id == 'R' && _components[1].Id == 'G' && _components[2].Id == 'B');
            var (c0, c1, c2) = (_components[0], _components[1], _components[2]);
            Parallel.For(0, _height, y =>
            {
                var row = samples.AsSpan(y * _width * 3, _width * 3);
                int r0 = Row(c0, y), r1 = Row(c1, y), r2 = Row(c2, y);
                int sx0 = _hMax / c0.H, sx1 = _hMax / c1.H, sx2 = _hMax / c2.H;
                for (int x = 0; x < _width; x++)
                {
                    int a = c0.Plane[r0 + x / sx0], b = c1.Plane[r1 + x / sx1], d = c2.Plane[r2 + x / sx2];
                    if (rgb) { row[3 * x] = (byte)a; row[3 * x + 1] = (byte)b; row[3 * x + 2] = (byte)d; continue; }
                    // T.871 §7: R = Y + 1.402 (Cr − 128), G = Y − 0.34414 (Cb − 128) − 0.71414 (Cr − 128),
                    // B = Y + 1.772 (Cb − 128), each product in 16-bit fixed point with one rounding (as the IJG's tables are).
                    int cb = b - 128, cr = d - 128;
                    row[3 * x] = Clamp(a + ((CrR * cr + Half) >> 16));
                    row[3 * x + 1] = Clamp(a + ((CbG * cb + CrG * cr + Half) >> 16));
                    row[3 * x + 2] = Clamp(a + ((CbB * cb + Half) >> 16));
                }
            });
            return new JpegImage(_width, _height, 3, samples);
        }

        /// <summary>The start of the plane row of <paramref name="c"/> that covers image row <paramref name="y"/>.</summary>
        int Row(Component c, int y) => y / (_vMax / c.V) * c.BlocksPerLine * 8;
    }

    const int Half = 1 << 15;
    static readonly int CrR = Fix16(1.40200), CbB = Fix16(1.77200), CbG = -Fix16(0.34414), CrG = -Fix16(0.71414);

    static int Fix16(double x) => (int)(x * 65536 + 0.5);

    static byte Clamp(int v) => (byte)Math.Clamp(v, 0, 255);

    /// <summary>Zig-zag position k → natural (row-major) index in the 8×8 block (T.81 Figure A.6).</summary>
    static readonly int[] ZigZag =
    [
        0, 1, 8, 16, 9, 2, 3, 10, 17, 24, 32, 25, 18, 11, 4, 5, 12, 19, 26, 33, 40, 48, 41, 34, 27, 20, 13, 6, 7, 14, 21,
        28, 35, 42, 49, 56, 57, 50, 43, 36, 29, 22, 15, 23, 30, 37, 44, 51, 58, 59, 52, 45, 38, 31, 39, 46, 53, 60, 61, 54,
        47, 55, 62, 63,
    ];

    // The LL&M inverse DCT in fixed point: constants c = round(x · 2^13), a first pass over columns keeping 2 more bits, a
    // second over rows that removes 13 + 2 + 3 bits (the 3 the 1/8 of the 2-D DCT's normalisation).
    const int ConstBits = 13, Pass1Bits = 2;
    const int F0298 = 2446, F0390 = 3196, F0541 = 4433, F0765 = 6270, F0899 = 7373, F1175 = 9633, F1501 = 12299,
        F1847 = 15137, F1961 = 16069, F2053 = 16819, F2562 = 20995, F3072 = 25172;

    /// <summary>8×8 dequantised coefficients (natural order) → samples level-shifted by +128 and clamped to 0–255, written at
    /// <paramref name="output"/> with the given row stride.</summary>
    static void InverseDct(Span<int> block, Span<int> ws, Span<byte> output, int stride)
    {
        for (int col = 0; col < 8; col++)
        {
            if (block[8 + col] == 0 && block[16 + col] == 0 && block[24 + col] == 0 && block[32 + col] == 0 && block[40 + col] == 0
                && block[48 + col] == 0 && block[56 + col] == 0)
            {
                int dc = block[col] << Pass1Bits;
                for (int r = 0; r < 8; r++) ws[8 * r + col] = dc;
                continue;
            }
            Butterfly(block[col], block[8 + col], block[16 + col], block[24 + col], block[32 + col], block[40 + col],
                block[48 + col], block[56 + col], ConstBits - Pass1Bits, ws, col, 8);
        }
        Span<int> row = stackalloc int[8];
        for (int r = 0; r < 8; r++)
        {
            var w = ws.Slice(8 * r, 8);
            var o = output.Slice(r * stride, 8);
            if (w[1] == 0 && w[2] == 0 && w[3] == 0 && w[4] == 0 && w[5] == 0 && w[6] == 0 && w[7] == 0)
            {
                byte dc = Clamp(Descale(w[0], Pass1Bits + 3) + 128);
                o.Fill(dc);
                continue;
            }
            Butterfly(w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7], ConstBits + Pass1Bits + 3, row, 0, 1);
            for (int x = 0; x < 8; x++) o[x] = Clamp(row[x] + 128);
        }
    }

    static int Descale(long x, int n) => (int)((x + (1L << (n - 1))) >> n);

    /// <summary>One 8-point inverse DCT (LL&amp;M): even part from inputs 0, 2, 4, 6, odd part from 1, 3, 5, 7, outputs descaled
    /// by <paramref name="shift"/> bits to <paramref name="o"/>[at + i·step].</summary>
    static void Butterfly(long i0, long i1, long i2, long i3, long i4, long i5, long i6, long i7, int shift, Span<int> o, int at, int step)
    {
        long z1 = (i2 + i6) * F0541;
        long t2 = z1 - i6 * F1847, t3 = z1 + i2 * F0765;
        long t0 = (i0 + i4) << ConstBits, t1 = (i0 - i4) << ConstBits;
        long e10 = t0 + t3, e13 = t0 - t3, e11 = t1 + t2, e12 = t1 - t2;

        long a = i7, b = i5, c = i3, d = i1;
        long y1 = a + d, y2 = b + c, y3 = a + c, y4 = b + d;
        long z5 = (y3 + y4) * F1175;
        a *= F0298; b *= F2053; c *= F3072; d *= F1501;
        y1 *= -F0899; y2 *= -F2562; y3 = y3 * -F1961 + z5; y4 = y4 * -F0390 + z5;
        a += y1 + y3; b += y2 + y4; c += y2 + y3; d += y1 + y4;

        o[at] = Descale(e10 + d, shift);
        o[at + 7 * step] = Descale(e10 - d, shift);
        o[at + step] = Descale(e11 + c, shift);
        o[at + 6 * step] = Descale(e11 - c, shift);
        o[at + 2 * step] = Descale(e12 + b, shift);
        o[at + 5 * step] = Descale(e12 - b, shift);
        o[at + 3 * step] = Descale(e13 + a, shift);
        o[at + 4 * step] = Descale(e13 - a, shift);
    }
}
