using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Tests.Diagnostics;

/// <summary>Messages are one printable line: control characters escaped, tokens quoted briefly, at most ~300 characters.</summary>
public class MessageTextTests
{
    [Theory]
    [InlineData("plain", "plain")]
    [InlineData("a\nb", "a\\nb")]
    [InlineData("x\r\ny", "x\\r\\ny")]
    [InlineData("\u001b[31mred\u001b[0m", "\\e[31mred\\e[0m")]
    [InlineData("nul\0byte", "nul\\0byte")]
    [InlineData("tab\there", "tab\\there")]
    [InlineData("bell\u0007", "bell\\u{0007}")]
    [InlineData("del\u007f", "del\\u{007F}")]
    [InlineData("c1\u009b", "c1\\u{009B}")]
    [InlineData("bidi\u202e", "bidi\\u{202E}")]
    [InlineData("λ 380–780 nm, ΔE00 …", "λ 380–780 nm, ΔE00 …")]
    public void Escape_makes_every_character_printable(string input, string expected) => Assert.Equal(expected, MessageText.Escape(input));

    [Fact]
    public void A_long_token_is_quoted_with_its_start_and_end()
    {
        var q = MessageText.Quote(new string('a', 1000) + "END");
        Assert.Equal(MessageText.MaxToken + 2, q.Length);
        Assert.StartsWith("'aaa", q);
        Assert.EndsWith("END'", q);
        Assert.Contains('…', q);
    }

    [Fact]
    public void Bytes_that_are_not_UTF_8_are_shown_as_replacement_characters()
    {
        Assert.Equal("'caf\uFFFD'", MessageText.Quote([(byte)'c', (byte)'a', (byte)'f', 0xE9]));
    }

    [Fact]
    public void A_message_with_a_10_KB_path_is_one_line_of_at_most_300_characters_that_keeps_what_and_hint()
    {
        var path = "/tmp/" + new string('d', 10_000) + "/x";
        var e = new InputException(path, "cannot be written: No such file\nor directory", "choose a folder you can write to");
        Assert.True(e.Message.Length <= MessageText.MaxLine, $"{e.Message.Length}");
        Assert.DoesNotContain('\n', e.Message);
        Assert.StartsWith("…ddd", e.Message);   // the place loses its beginning, not its file name
        Assert.Contains("/x: cannot be written: No such file\\nor directory (hint: choose a folder you can write to)", e.Message);
    }

    /// <summary>
    /// Issue 42: a long folder path cut the reason in the middle ("material 'pri… a dispersive split yet"). The place
    /// is cut first (keeping the file, line:column and JSON path), then the hint, and the reason only when nothing else is left.
    /// </summary>
    [Theory]
    [InlineData(40)]
    [InlineData(200)]
    [InlineData(2000)]
    public void A_long_place_is_cut_before_the_reason(int folderLength)
    {
        var where = "/home/user/" + new string('f', folderLength) + "/scenes/booth.json:12:7: $.materials.prism";
        var what = "material 'prism-of-a-long-descriptive-name' is dispersive and fluorescent: the path tracer has no"
            + " dispersive split for it yet";
        var hint = "give the prism a constant ior or remove its fluorescence";
        var message = new InputException(where, what, hint).Message;
        Assert.True(message.Length <= MessageText.MaxLine, $"{message.Length}: {message}");
        Assert.Contains(what, message);
        Assert.Contains("booth.json:12:7: $.materials.prism: ", message);
        Assert.EndsWith($" (hint: {hint})", message);
    }

    [Fact]
    public void When_the_reason_alone_is_too_long_the_place_keeps_its_file_and_the_reason_its_start_and_end()
    {
        var message = new InputException("/" + new string('d', 500) + "/scene.json: $.x", "starts " + new string('r', 600) + " ends",
            "a hint").Message;
        Assert.True(message.Length <= MessageText.MaxLine, $"{message.Length}");
        Assert.Contains("scene.json: $.x: starts rrr", message);
        Assert.Contains("rrr ends (hint: a hint)", message);
    }
}
