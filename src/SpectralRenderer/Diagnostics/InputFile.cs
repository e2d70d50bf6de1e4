using System.Text;

namespace SpectralRenderer.Diagnostics;

/// <summary>
/// Reads an input file whole, turning every way it cannot be used into one <see cref="InputException"/> line.
/// Only regular files are read: a FIFO, a device or a symbolic link to one reports a size of 0 without being
/// opened (opening a FIFO blocks, a device never ends), and a file larger than the limit is refused before a
/// byte of it is read. The bytes read are exactly the size the file system reported, so a file that grows
/// while it is read cannot make the tool hold more.
/// </summary>
public static class InputFile
{
    /// <summary>The largest input file (meshes, images, cubes): 1 GiB.</summary>
    public const long MaxBytes = 1L << 30;

    /// <summary>The largest text input (scene files, spectral CSV, headers): 256 MiB.</summary>
    public const long MaxTextBytes = 256L << 20;

    public static byte[] ReadAllBytes(string path, string what = "file", long maxBytes = MaxBytes)
    {
        long length = CheckedLength(path, what, maxBytes);
        try
        {
            using var fs =
                new FileStream(path, FileMode.Open, FileAccess.Read, FileShare.ReadWrite | FileShare.Delete, 1, FileOptions.None);
            var bytes = new byte[length];
            int read = 0;
            while (read < bytes.Length)
            {
                int n = fs.Read(bytes, read, bytes.Length - read);
                if (n == 0)
                    throw new InputException(path, $"{what} shrank while it was read ({read} of {length} bytes)",
                        "do not change the file while spectral reads it");
                read += n;
            }
            return bytes;
        }
        catch (Exception e) when (e is FileNotFoundException or DirectoryNotFoundException)
        {
            throw new InputException(path, $"{what} not found", "check the path") { Problem = InputProblem.MissingFile };
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException)
        {
            throw new InputException(path, $"{what} cannot be read: {e.Message}",
                "check the file's permissions and that it is a file, not a folder");
        }
    }

    /// <summary>The file as text (UTF-8, or UTF-16/32 by its byte order mark), within <see cref="MaxTextBytes"/>.</summary>
    public static string ReadAllText(string path, string what = "file", long maxBytes = MaxTextBytes)
    {
        var bytes = ReadAllBytes(path, what, maxBytes);
        using var reader = new StreamReader(new MemoryStream(bytes), Encoding.UTF8, detectEncodingFromByteOrderMarks: true);
        return reader.ReadToEnd();
    }

    /// <summary>The size of a regular file within <paramref name="maxBytes"/>, or the one-line reason it cannot be read.</summary>
    public static long CheckedLength(string path, string what = "file", long maxBytes = MaxBytes)
    {
        if (string.IsNullOrEmpty(path)) throw new InputException("(empty path)", $"no {what} named", "give a file name");
        FileInfo info;
        try { info = new FileInfo(path); }
        catch (Exception e) when (e is ArgumentException or NotSupportedException or PathTooLongException)
        {
            throw new InputException(path, $"is not a usable file name: {e.Message}", "check the path");
        }
        if (Directory.Exists(path)) throw new InputException(path, $"{what} is a folder", "give the path of a file");
        if (info.LinkTarget is { } link)
        {
            // FileInfo describes the link itself (its length is that of the target's name): look at where it leads.
            FileSystemInfo? target;
            try { target = File.ResolveLinkTarget(path, returnFinalTarget: true); }
            catch (IOException) { target = null; }
            if (target is null || !target.Exists)
                throw new InputException(path, $"{what} is a symbolic link to {MessageText.Quote(link, 80)}, which does not exist",
                    "fix or remove the link");
            if (target is DirectoryInfo)
                throw new InputException(path, $"{what} is a symbolic link to a folder", "give the path of a file");
            info = (FileInfo)target;
        }
        if (!info.Exists) throw new InputException(path, $"{what} not found", "check the path");
        long length = info.Length;
        if (length == 0)
            throw new InputException(path, $"{what} is empty or not a regular file (a FIFO, socket or device reports no size)",
                "give a regular file with content; spectral does not read pipes or devices");
        if (length > maxBytes)
            throw new InputException(path, $"{what} is {Size(length)}, more than the limit of {Size(maxBytes)}", "give a smaller file");
        return length;
    }

    public static string Size(long bytes) => bytes >= 1L << 30 ? $"{bytes / (double)(1L << 30):0.#} GiB"
        : bytes >= 1L << 20 ? $"{bytes / (double)(1L << 20):0.#} MiB" : bytes >= 1L << 10 ? $"{bytes / 1024.0:0.#} KiB" : $"{bytes} bytes";
}
