using SpectralRenderer.Diagnostics;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Tests.Spectra;

public class CsvSpectrumReaderTests
{
    [Fact]
    public void Reads_named_columns()
    {
        var t = CsvSpectrumReader.Parse("wavelength_nm,a,b c\n400,0.1,1\n410,0.2,2\n", "x.csv");
        Assert.Equal(["a", "b c"], t.Columns);
        Assert.Equal(0.15, t["a"].Evaluate(405), 14);
        Assert.Equal(2.0, t["b c"].Evaluate(410));
    }

    [Fact]
    public void Every_shipped_data_file_reads()
    {
        // The CIE daylight basis S1, S2 goes negative by definition: it is read as a signed table.
        foreach (var f in Directory.GetFiles(DataDirectory.Path, "*.csv"))
            Assert.NotEmpty(
                (Path.GetFileName(f) == "cie-daylight-components.csv" ? CsvSpectrumReader.ReadSigned(f) : CsvSpectrumReader.Read(f))
                .Columns);
        Assert.Throws<SpectralRenderer.Diagnostics.InputException>(() =>
            CsvSpectrumReader.Read(Path.Combine(DataDirectory.Path, "cie-daylight-components.csv")));
    }

    [Theory]
    [InlineData("wavelength_nm,a\n400,0.1\n410,x\n", "bad.csv:3:2:", "'x' in column 'a' is not a number")]
    [InlineData("wavelength_nm,a,b\n400,0.1,0.2\n410,0.3\n", "bad.csv:3:3:", "missing column")]
    [InlineData("wavelength_nm,a\n400,0.1\n390,0.2\n", "bad.csv:3:1:", "not ascending")]
    [InlineData("wavelength_nm,a\n400,0.1\n400,0.2\n", "bad.csv:3:1:", "appears twice")]
    [InlineData("wavelength_nm,a\n400,0.1\n410,NaN\n", "bad.csv:3:2:", "not finite")]
    [InlineData("wavelength_nm,a\n400,Infinity\n", "bad.csv:2:2:", "not finite")]
    [InlineData("wavelength_nm,a\n400,0.1\n410,-0.2\n", "bad.csv:3:2:", "negative value -0.2")]
    [InlineData("", "bad.csv:1:1:", "empty")]
    [InlineData("\n\n", "bad.csv:1:1:", "empty")]
    [InlineData("wavelength_nm,a\n", "bad.csv:2:1:", "no data rows")]
    [InlineData("wavelength_nm\n400\n", "bad.csv:1:2:", "fewer than two columns")]
    [InlineData("wavelength_nm,a,a\n400,1,1\n", "bad.csv:1:3:", "column name 'a' appears twice")]
    [InlineData("wavelength_nm,,a\n400,1,1\n", "bad.csv:1:2:", "column 2 has no name")]
    [InlineData("wavelength_nm,a\n400,1,2\n", "bad.csv:2:3:", "the header names only 2")]
    [InlineData("wavelength_nm,a\n400,1\n\n410,1\n", "bad.csv:3:1:", "empty line inside the data")]
    [InlineData("wavelength_nm,a\n0,1\n", "bad.csv:2:1:", "not positive")]
    public void Broken_files_are_rejected_with_file_row_and_column(string text, string where, string what)
    {
        var e = Assert.Throws<InputException>(() => CsvSpectrumReader.Parse(text, "bad.csv"));
        Assert.StartsWith(where, e.Message);
        Assert.Contains(what, e.Message);
    }

    [Fact]
    public void A_missing_file_names_the_file()
    {
        var e = Assert.Throws<InputException>(() => CsvSpectrumReader.Read("/nonexistent/spectra.csv"));
        Assert.StartsWith("/nonexistent/spectra.csv: file not found", e.Message);
    }
}
