using System.Globalization;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Rendering;

/// <summary>
/// A rectangle of the film in pixel coordinates of the whole image: columns X0 … X1 − 1, rows Y0 … Y1 − 1
/// (half-open, row 0 at the top), as <c>--crop X0,Y0,X1,Y1</c> writes it.
/// </summary>
public readonly record struct PixelRect(int X0, int Y0, int X1, int Y1)
{
    public int Width => X1 - X0;
    public int Height => Y1 - Y0;
    public long Pixels => (long)Width * Height;

    public static PixelRect Whole(int width, int height) => new(0, 0, width, height);

    public bool IsWhole(int width, int height) => X0 == 0 && Y0 == 0 && X1 == width && Y1 == height;

    public bool Overlaps(PixelRect o) => X0 < o.X1 && o.X0 < X1 && Y0 < o.Y1 && o.Y0 < Y1;

    /// <summary>Parses "X0,Y0,X1,Y1" and checks it lies inside a width × height image and is not empty.</summary>
    public static PixelRect Parse(string text, int width, int height, string where = "--crop")
    {
        var parts = text.Split(',');
        var v = new int[4];
        if (parts.Length != 4
            || !parts.Select((p, i) => int.TryParse(p.Trim(), NumberStyles.Integer, CultureInfo.InvariantCulture, out v[i])).All(ok => ok))
            throw new InputException(where, $"'{text}' is not X0,Y0,X1,Y1 (four whole numbers)",
                "e.g. --crop 0,0,512,256: columns 0–511, rows 0–255");
        var r = new PixelRect(v[0], v[1], v[2], v[3]);
        if (r.X0 < 0 || r.Y0 < 0 || r.X1 > width || r.Y1 > height || r.Width < 1 || r.Height < 1)
            throw new InputException(where, $"{r} is not a non-empty rectangle inside the {width}×{height} image",
                "X1 and Y1 are exclusive: 0 ≤ X0 < X1 ≤ width, 0 ≤ Y0 < Y1 ≤ height");
        return r;
    }

    public override string ToString() => string.Create(CultureInfo.InvariantCulture, $"{X0},{Y0},{X1},{Y1}");
}
