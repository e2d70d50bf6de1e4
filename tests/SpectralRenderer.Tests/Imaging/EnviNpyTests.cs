using System.Buffers.Binary;
using System.Text;
using SpectralRenderer.Diagnostics;
using SpectralRenderer.Imaging;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Imaging;

public class EnviTests
{
    [Fact]
    public void Round_trip_is_bit_exact_and_data_is_band_sequential()
    {
        var dir = Reference.TempDir();
        var img = Synthetic.Image();
        var path = Path.Combine(dir, "spectral.img");
        EnviWriter.Write(path, img, "test cube");
        Assert.Equal(new[] { "spectral.hdr", "spectral.img" }, Directory.GetFiles(dir).Select(Path.GetFileName).Order());
        var back = EnviReader.Read(path);
        Assert.Equal(BandGrid.Default, back.Grid);
        Assert.Equal((img.Width, img.Height), (back.Width, back.Height));
        Synthetic.AssertBitExact(img.Data, back.Data, "ENVI");

        var raw = File.ReadAllBytes(path);
        Assert.Equal(img.Data.Length * 4, raw.Length);
        int n = img.Width * img.Height;
        // BSQ: band b, row y, column x at ((b·H + y)·W + x)·4, little-endian.
        foreach (var (x, y, b) in new[] { (0, 0, 0), (36, 0, 0), (3, 7, 0), (36, 22, 19), (11, 4, 9) })
            Assert.Equal(img[x, y, b], BinaryPrimitives.ReadSingleLittleEndian(raw.AsSpan(4 * (b * n + y * img.Width + x))));
    }

    [Fact]
    public void Uneven_grid_comes_back_equal()
    {
        var dir = Reference.TempDir();
        var grid = new BandGrid(400, 700, 31);
        var img = Synthetic.Image(grid);
        EnviWriter.Write(Path.Combine(dir, "spectral.img"), img);
        var back = EnviReader.Read(Path.Combine(dir, "spectral.img"));
        Assert.Equal(grid, back.Grid);
        Synthetic.AssertBitExact(img.Data, back.Data, "31 bands");
        WavelengthsCsv.Write(Path.Combine(dir, "wavelengths.csv"), grid);
        Assert.Equal(grid, WavelengthsCsv.Read(Path.Combine(dir, "wavelengths.csv")));
    }

    [Fact]
    public void Header_has_the_ENVI_keys_wavelengths_and_fwhm()
    {
        var h = EnviWriter.Header(Synthetic.Image(), "a {braced} description");
        var lines = h.Split('\n');
        Assert.Equal("ENVI", lines[0]);
        Assert.Contains("description = {a (braced) description}", lines);
        foreach (var l in new[] { "samples = 37", "lines = 23", "bands = 20", "header offset = 0", "file type = ENVI Standard",
                     "data type = 4", "interleave = bsq", "byte order = 0", "wavelength units = Nanometers" })
            Assert.Contains(l, lines);
        Assert.Contains("wavelength = {390, 410, 430, ", h);
        Assert.Contains(", 770}", h);
        Assert.Contains("fwhm = {20, 20, ", h);
        Assert.Contains("band names = {380-400 nm, 400-420 nm, ", h);
    }

    [Fact]
    public void Header_parser_reads_multi_line_braces_and_other_tools_spelling()
    {
        var text = "ENVI\r\ndescription = {\r\n  written by hand,\r\n  over lines}\r\nsamples = 2\nlines=1\nBands = 3\n" +
                   "data type = 4\ninterleave = bip\nbyte order = 1\nwavelength units = Micrometers\n" +
                   "wavelength = {\n 0.41,\n 0.43 ,0.45\n}\n; a comment = {x}\n";
        var h = EnviReader.ParseHeader(text);
        Assert.Equal("written by hand,   over lines", h["description"].Replace("\r", ""));
        Assert.Equal("3", h["bands"]);
        Assert.Equal("1", h["lines"]);
        var data = new byte[2 * 1 * 3 * 4];
        for (int i = 0; i < 6; i++) BinaryPrimitives.WriteSingleBigEndian(data.AsSpan(4 * i), i + 0.5f);
        var img = EnviReader.ReadData(new MemoryStream(data), h);
        Assert.Equal(new BandGrid(400, 460, 3), img.Grid);
        Assert.Equal(new[] { 0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f }, img.Data);   // BIP is our own pixel-interleaved order
    }

    [Fact]
    public void Bad_input_is_an_input_error()
    {
        var dir = Reference.TempDir();
        var path = Path.Combine(dir, "spectral.img");
        EnviWriter.Write(path, Synthetic.Image());
        File.WriteAllBytes(path, File.ReadAllBytes(path)[..1000]);
        Assert.Contains("truncated", Assert.Throws<InputException>(() => EnviReader.Read(path)).Message);
        File.WriteAllText(EnviWriter.HeaderPath(path),
            File.ReadAllText(EnviWriter.HeaderPath(path)).Replace("data type = 4", "data type = 12"));
        Assert.Contains("data type 12", Assert.Throws<InputException>(() => EnviReader.Read(path)).Message);
        Assert.Throws<InputException>(() => EnviReader.ParseHeader("P6\n"));
    }
}

public class NpyTests
{
    [Fact]
    public void Header_is_version_1_0_padded_to_64_bytes()
    {
        var ms = new MemoryStream();
        NpyWriter.Write(ms, Synthetic.Image());
        var b = ms.ToArray();
        Assert.Equal(new byte[] { 0x93, (byte)'N', (byte)'U', (byte)'M', (byte)'P', (byte)'Y', 1, 0 }, b[..8]);
        int len = BinaryPrimitives.ReadUInt16LittleEndian(b.AsSpan(8));
        Assert.Equal(0, (10 + len) % 64);
        var header = Encoding.ASCII.GetString(b, 10, len);
        Assert.Equal("{'descr': '<f4', 'fortran_order': False, 'shape': (23, 37, 20), }", header.TrimEnd(' ', '\n'));
        Assert.EndsWith(" \n", header);
        Assert.Equal(10 + len + 23 * 37 * 20 * 4, b.Length);
        var img = Synthetic.Image();
        // C order: [y, x, b] at ((y·W + x)·N + b).
        Assert.Equal(img[5, 3, 7], BinaryPrimitives.ReadSingleLittleEndian(b.AsSpan(10 + len + 4 * ((3 * 37 + 5) * 20 + 7))));
    }

    [Fact]
    public void Round_trip_is_bit_exact_with_wavelengths_csv()
    {
        var dir = Reference.TempDir();
        var img = Synthetic.Image();
        NpyWriter.Write(Path.Combine(dir, "spectral.npy"), img);
        WavelengthsCsv.Write(Path.Combine(dir, "wavelengths.csv"), img.Grid);
        var lines = File.ReadAllLines(Path.Combine(dir, "wavelengths.csv"));
        Assert.Equal(21, lines.Length);
        Assert.Equal("band,start_nm,centre_nm,end_nm", lines[0]);
        Assert.Equal("1,380,390,400", lines[1]);   // bands are numbered from 1
        Assert.Equal("20,760,770,780", lines[20]);
        var grid = WavelengthsCsv.Read(Path.Combine(dir, "wavelengths.csv"));
        Assert.Equal(img.Grid, grid);
        var back = NpyReader.ReadImage(Path.Combine(dir, "spectral.npy"), grid);
        Synthetic.AssertBitExact(img.Data, back.Data, "NPY");
        Assert.Equal((37, 23), (back.Width, back.Height));
        var auto = NpyReader.ReadImage(Path.Combine(dir, "spectral.npy"));
        Assert.Equal(img.Grid, auto.Grid);
        Synthetic.AssertBitExact(img.Data, auto.Data, "NPY + wavelengths.csv");
    }

    [Fact]
    public void Bad_input_is_an_input_error()
    {
        var ms = new MemoryStream();
        NpyWriter.Write(ms, Synthetic.Image());
        var b = ms.ToArray();
        Assert.Contains("truncated", Assert.Throws<InputException>(() => NpyReader.Read(new MemoryStream(b[..500]))).Message);
        Assert.Contains("magic", Assert.Throws<InputException>(() => NpyReader.Read(new MemoryStream("not numpy"u8.ToArray()))).Message);
        Assert.Contains("bands",
            Assert.Throws<InputException>(() => NpyReader.ReadImage(new MemoryStream(b), new BandGrid(400, 700, 31))).Message);
    }
}
