namespace SpectralRenderer.Diagnostics;

/// <summary>Reads an input file whole, turning a missing or unreadable file into one <see cref="InputException"/> line.</summary>
public static class InputFile
{
    public static byte[] ReadAllBytes(string path, string what = "file") => Read(path, what, File.ReadAllBytes);

    public static string ReadAllText(string path, string what = "file") => Read(path, what, File.ReadAllText);

    static T Read<T>(string path, string what, Func<string, T> read)
    {
        try { return read(path); }
        catch (Exception e) when (e is FileNotFoundException or DirectoryNotFoundException)
        {
            throw new InputException(path, $"{what} not found", "check the path") { Problem = InputProblem.MissingFile };
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException)
        {
            throw new InputException(path, $"cannot be read: {e.Message}");
        }
    }
}
