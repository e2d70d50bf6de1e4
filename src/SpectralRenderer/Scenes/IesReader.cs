using System.Globalization;
using System.Numerics;
using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes;

/// <summary>A photometric file read: its candela table (multipliers applied) and what it says about its lamps.</summary>
/// <param name="LampLumens">Rated lumens of all lamps (relative photometry), or null for absolute photometry.</param>
public sealed record PhotometricFile(CandelaTable Table, double? LampLumens, string Format)
{
    /// <summary>An IES file's TILT=INCLUDE block, or null (TILT=NONE, EULUMDAT).</summary>
    public LampTilt? Tilt { get; init; }
}

/// <summary>
/// IES LM-63's TILT=INCLUDE data: candela multiplying factors against the lamp's tilt from the position it was measured
/// in. <see cref="Geometry"/> is the lamp-to-luminaire geometry: 1, the lamp vertical (base up or down) with the
/// luminaire aimed down; 2, the lamp horizontal and staying so when the luminaire tilts in its C0–C180 plane (its axis
/// along C90–C270); 3, the lamp horizontal along C0–C180 (staying so when tilted in the C90–C270 plane).
/// </summary>
public sealed record LampTilt(int Geometry, double[] Angles, double[] Factors)
{
    /// <summary>The lamp's axis in the luminaire frame of <see cref="GoniometricLight"/> (nadir −y, C0 +x, C90 −z).</summary>
    public Vector3 LampAxis => Geometry switch { 1 => Vector3.UnitY, 2 => Vector3.UnitZ, _ => Vector3.UnitX };

    /// <summary>
    /// The lamp's tilt in degrees when the luminaire frame is turned into the world by <paramref name="orientation"/>:
    /// the angle of its axis from the vertical (geometry 1) or from the horizontal (2, 3), as it was measured.
    /// </summary>
    public double TiltDegrees(Matrix4x4 orientation)
    {
        var axis = Vector3.Normalize(Vector3.TransformNormal(LampAxis, orientation));
        double up = Math.Min(1, Math.Abs((double)axis.Y));
        return (Geometry == 1 ? Math.Acos(up) : Math.Asin(up)) * 180 / Math.PI;
    }

    /// <summary>The factor at <paramref name="degrees"/>: linear between the file's angles, its end values beyond them.</summary>
    public double Factor(double degrees)
    {
        if (degrees <= Angles[0]) return Factors[0];
        for (int i = 1; i < Angles.Length; i++)
            if (degrees <= Angles[i])
                return Factors[i - 1] + (Factors[i] - Factors[i - 1]) * (degrees - Angles[i - 1]) / (Angles[i] - Angles[i - 1]);
        return Factors[^1];
    }
}

/// <summary>
/// IES LM-63 (-1995, -2002, -2019) photometric files, type C: keyword lines up to TILT=, then the numbers — lamps,
/// lumens per lamp (−1: absolute photometry), candela multiplier, vertical and horizontal angle counts, photometric type,
/// units, dimensions; ballast factor, ballast-lamp photometric factor (LM-63-2002 "future use"), input watts; the vertical
/// angles, the horizontal angles, and the candela values plane by plane. Candela = value × multiplier × ballast factor ×
/// ballast-lamp factor. Symmetry from the horizontal angles (LM-63-2019 §5.10): one angle (0) axial, last 90 quadrant,
/// last 180 bilateral, first 90 and last 270 bilateral about C90–C270, last 360 full; TILT=INCLUDE factors (LampTilt). Errors: file:line, a
/// hint.
/// </summary>
public static class IesReader
{
    const int MaxAngles = 100_000;

    public static PhotometricFile Parse(string text, string file)
    {
        var lines = text.Replace("\r\n", "\n").Replace('\r', '\n').TrimEnd('\n').Split('\n');
        int l = 0;
        if (lines.Length == 0 || lines.All(string.IsNullOrWhiteSpace))
            throw new InputException($"{file}:1", "the file is empty",
                "an IES LM-63 file starts with IESNA:LM-63-2002 and has a TILT= line");
        while (l < lines.Length && !lines[l].TrimStart().StartsWith("TILT", StringComparison.OrdinalIgnoreCase)) l++;
        if (l == lines.Length)
            throw new InputException($"{file}:{lines.Length}", "no TILT= line",
                "an IES LM-63 file has TILT=NONE (or INCLUDE) before its numbers");
        var tilt = lines[l].Trim();
        int eq = tilt.IndexOf('=');
        string mode = eq < 0 ? "" : tilt[(eq + 1)..].Trim();
        var tokens = new Tokens(lines, l + 1, file);
        LampTilt? lampTilt = null;
        if (mode.Equals("INCLUDE", StringComparison.OrdinalIgnoreCase))
        {
            // Lamp-to-luminaire geometry, the number of tilt angles, the angles (0–90°, ascending), the factors: the
            // light multiplies its candela by the factor at the tilt its "rotate" gives the lamp (GoniometricLight).
            int geometry = tokens.Count("the lamp-to-luminaire geometry", 1, 3);
            int n = tokens.Count("the number of tilt angles", 1, MaxAngles);
            var angles = tokens.Angles("tilt", n, 0, 90);
            var factors = new double[n];
            for (int i = 0; i < n; i++) factors[i] = tokens.NonNegative("a tilt factor");
            lampTilt = new LampTilt(geometry, angles, factors);
        }
        else if (!mode.Equals("NONE", StringComparison.OrdinalIgnoreCase))
            throw new InputException($"{file}:{l + 1}", $"TILT={MessageText.Quote(mode, 40)} is not supported",
                "use TILT=NONE or TILT=INCLUDE");

        int lamps = tokens.Count("the number of lamps", 1, 1000);
        double lumens = tokens.Number("the lumens per lamp");
        double multiplier = tokens.Positive("the candela multiplier");
        int nv = tokens.Count("the number of vertical angles", 1, MaxAngles);
        int nh = tokens.Count("the number of horizontal angles", 1, MaxAngles);
        int type = tokens.Count("the photometric type", 1, 3);
        if (type != 1)
            throw tokens.Error($"photometric type {type} ({(type == 2 ? "B" : "A")}) is not supported",
                "type C (1), the type of almost all building luminaires");
        tokens.Count("the units type", 1, 2);
        for (int i = 0; i < 3; i++) tokens.Number("a luminous opening dimension");
        double ballast = tokens.NonNegative("the ballast factor");
        double ballastLamp = tokens.NonNegative("the ballast-lamp photometric factor");
        tokens.Number("the input watts");
        var vertical = tokens.Angles("vertical", nv, 0, 180);
        if (vertical[0] != 0 && vertical[0] != 90)
            throw tokens.Error($"the first vertical angle is {vertical[0]:0.###}",
                "type C vertical angles start at 0 (or 90 for an uplight)");
        var horizontal = tokens.Angles("horizontal", nh, 0, 360);
        CandelaSymmetry symmetry;
        if (nh == 1 && horizontal[0] == 0) symmetry = CandelaSymmetry.Axial;
        else if (horizontal[0] == 0 && horizontal[^1] == 90) symmetry = CandelaSymmetry.Quadrant;
        else if (horizontal[0] == 0 && horizontal[^1] == 180) symmetry = CandelaSymmetry.BilateralC0;
        else if (horizontal[0] == 90 && horizontal[^1] == 270) symmetry = CandelaSymmetry.BilateralC90;
        else if (horizontal[0] == 0 && horizontal[^1] == 360) symmetry = CandelaSymmetry.Full;
        else throw tokens.Error($"horizontal angles {horizontal[0]:0.###} … {horizontal[^1]:0.###} match no LM-63 symmetry",
            "type C horizontal angles are 0 (axial), 0–90, 0–180, 90–270 or 0–360 (LM-63-2019 §5.10)");
        double factor = multiplier * ballast * ballastLamp;
        var rows = new double[nh][];
        for (int h = 0; h < nh; h++)
        {
            rows[h] = new double[nv];
            for (int v = 0; v < nv; v++) rows[h][v] = tokens.NonNegative("a candela value") * factor;
        }
        tokens.End();
        return new PhotometricFile(new CandelaTable(vertical, horizontal, rows, symmetry, file), lumens > 0 ? lamps * lumens : null,
            "IES LM-63")
        { Tilt = lampTilt };
    }

    /// <summary>The numbers of a text, with the line each came from, for errors.</summary>
    sealed class Tokens
    {
        readonly List<(string Text, int Line)> _items = [];
        readonly string _file;
        int _next;
        int _lastLine;

        public Tokens(string[] lines, int from, string file)
        {
            _file = file;
            _lastLine = Math.Max(from, 1);
            for (int l = from; l < lines.Length; l++)
                foreach (var t in lines[l].Split([' ', '\t', ','], StringSplitOptions.RemoveEmptyEntries))
                    _items.Add((t, l + 1));
        }

        public InputException Error(string what, string hint) => new($"{_file}:{_lastLine}", what, hint);

        public double Number(string what)
        {
            if (_next >= _items.Count)
                throw new InputException($"{_file}:{_lastLine}", $"the file ends before {what}",
                    "the file is cut short: check the angle counts against the values");
            var (text, line) = _items[_next++];
            _lastLine = line;
            if (!double.TryParse(text, NumberStyles.Float, CultureInfo.InvariantCulture, out double v) || !double.IsFinite(v))
                throw new InputException($"{_file}:{line}", $"{what} is {MessageText.Quote(text, 40)}, not a number",
                    "IES values are plain decimal numbers");
            return v;
        }

        public double NonNegative(string what)
        {
            double v = Number(what);
            return v >= 0 ? v : throw Error($"{what} is negative ({v:g})", "candela values and factors are ≥ 0");
        }

        public double Positive(string what)
        {
            double v = Number(what);
            return v > 0 ? v : throw Error($"{what} is {v:g}", "it must be positive");
        }

        public int Count(string what, int min, int max)
        {
            double v = Number(what);
            return v == Math.Floor(v) && v >= min && v <= max
                ? (int)v
                : throw Error($"{what} is {v:g}", $"a whole number from {min} to {max}");
        }

        public double[] Angles(string kind, int n, double min, double max)
        {
            var a = new double[n];
            for (int i = 0; i < n; i++)
            {
                a[i] = Number($"{kind} angle {i + 1} of {n}");
                if (a[i] < min || a[i] > max)
                    throw Error($"{kind} angle {a[i]:g} is outside {min:g}–{max:g}°", $"type C {kind} angles lie in {min:g}–{max:g}°");
                if (i > 0 && !(a[i] > a[i - 1]))
                    throw Error($"{kind} angles are not ascending ({a[i - 1]:g} then {a[i]:g})", "list the angles in increasing order");
            }
            return a;
        }

        public void End()
        {
            if (_next < _items.Count)
                throw new InputException($"{_file}:{_items[_next].Line}", $"{_items.Count - _next} values after the candela table",
                    "the angle counts say where the table ends: check them");
        }
    }
}
