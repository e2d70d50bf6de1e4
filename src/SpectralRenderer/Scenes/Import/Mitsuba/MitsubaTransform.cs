using SpectralRenderer.Diagnostics;

namespace SpectralRenderer.Scenes.Import.Mitsuba;

/// <summary>
/// A Mitsuba &lt;transform&gt;: its operations (translate, rotate, scale, matrix, lookat) in document order, each applied after
/// the ones before it (M = op_n ⋯ op_1), as a row-major 4 × 4 matrix acting on column vectors.
/// </summary>
public static class MitsubaTransform
{
    public static double[] Identity => RowMajorMatrix.Identity;

    /// <summary>The matrix of a &lt;transform&gt; element.</summary>
    public static double[] Of(MitsubaElement transform)
    {
        var m = Identity;
        foreach (var op in transform.Children) m = Multiply(Operation(op), m);
        return m;
    }

    static double[] Operation(MitsubaElement op)
    {
        switch (op.Tag)
        {
            case "translate":
                {
                    var t = Vector(op, 0);
                    return [1, 0, 0, t[0], 0, 1, 0, t[1], 0, 0, 1, t[2], 0, 0, 0, 1];
                }
            case "scale":
                {
                    var s = Vector(op, 1);
                    return [s[0], 0, 0, 0, 0, s[1], 0, 0, 0, 0, s[2], 0, 0, 0, 0, 1];
                }
            case "rotate":
                {
                    var axis = Vector(op, 0);
                    double angle = op.Attr("angle") is { } a ? Number(a, op) : 0;
                    return Rotation(axis, angle, op);
                }
            case "matrix":
                {
                    var v = MitsubaXml.Numbers(op.Attr("value") ?? "", op.Where, "matrix");
                    if (v.Length == 9) return [v[0], v[1], v[2], 0, v[3], v[4], v[5], 0, v[6], v[7], v[8], 0, 0, 0, 0, 1];
                    if (v.Length != 16)
                        throw new InputException(op.Where, $"<matrix> has {v.Length} numbers, expected 16 (or 9)",
                            "row-major, e.g. value=\"1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\"");
                    return v;
                }
            case "lookat":
                {
                    var o = Point(op, "origin");
                    var t = Point(op, "target");
                    var up = op.Attr("up") is null ? [0, 1, 0] : Point(op, "up");
                    return LookAt(o, t, up, op);
                }
            default:
                throw new InputException(op.Where, $"<{op.Tag}> is not a transform operation",
                    "use translate, rotate, scale, matrix or lookat");
        }
    }

    /// <summary>Mitsuba's look_at: columns left = normalize(up × dir), up' = dir × left, dir, origin (the camera looks along +z).</summary>
    public static double[] LookAt(double[] o, double[] t, double[] up, MitsubaElement where)
    {
        var d = Normalize(Sub(t, o), where, "target equals origin");
        var left = Normalize(Cross(Normalize(up, where, "up is zero"), d), where, "up is parallel to the viewing direction");
        var newUp = Cross(d, left);
        return [left[0], newUp[0], d[0], o[0], left[1], newUp[1], d[1], o[1], left[2], newUp[2], d[2], o[2], 0, 0, 0, 1];
    }

    /// <summary>A rotation by <paramref name="degrees"/> about <paramref name="axis"/> (right-handed, Rodrigues).</summary>
    static double[] Rotation(double[] axis, double degrees, MitsubaElement where)
    {
        var a = Normalize(axis, where, "the rotation axis is zero");
        double th = degrees * Math.PI / 180, c = Math.Cos(th), s = Math.Sin(th), k = 1 - c;
        double x = a[0], y = a[1], z = a[2];
        return
        [
            c + x * x * k, x * y * k - z * s, x * z * k + y * s, 0,
            y * x * k + z * s, c + y * y * k, y * z * k - x * s, 0,
            z * x * k - y * s, z * y * k + x * s, c + z * z * k, 0,
            0, 0, 0, 1,
        ];
    }

    public static double[] Multiply(double[] a, double[] b) => RowMajorMatrix.Multiply(a, b);

    /// <summary>M·p for a point (w = 1) or a direction (w = 0).</summary>
    public static double[] Apply(double[] m, double[] p, double w) =>
    [
        m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3] * w,
        m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7] * w,
        m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11] * w,
    ];

    /// <summary>The determinant of the linear (upper-left 3 × 3) part.</summary>
    public static double Determinant(double[] m) =>
        m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) + m[2] * (m[4] * m[9] - m[5] * m[8]);

    static double[] Vector(MitsubaElement op, double fallback)
    {
        if (op.Attr("value") is { } v)
        {
            var n = MitsubaXml.Numbers(v, op.Where, op.Tag);
            if (n.Length == 1) return [n[0], n[0], n[0]];
            if (n.Length == 3) return n;
            throw new InputException(op.Where, $"<{op.Tag}> value has {n.Length} numbers, expected 1 or 3", "e.g. value=\"1, 2, 3\"");
        }
        return
        [
            op.Attr("x") is { } x ? Number(x, op) : fallback,
            op.Attr("y") is { } y ? Number(y, op) : fallback,
            op.Attr("z") is { } z ? Number(z, op) : fallback,
        ];
    }

    static double[] Point(MitsubaElement op, string name)
    {
        var text = op.Attr(name)
            ?? throw new InputException(op.Where, $"<lookat> without {name}", "give origin, target and up, e.g. origin=\"0, 1, 5\"");
        var v = MitsubaXml.Numbers(text, op.Where, name);
        if (v.Length != 3) throw new InputException(op.Where, $"{name} has {v.Length} numbers, expected 3", "e.g. \"0, 1, 5\"");
        return v;
    }

    static double Number(string text, MitsubaElement op)
    {
        var v = MitsubaXml.Numbers(text, op.Where, op.Tag);
        if (v.Length != 1)
            throw new InputException(op.Where, $"expected one number, found {MessageText.Quote(text, 30)}", "e.g. angle=\"90\"");
        return v[0];
    }

    public static double[] Sub(double[] a, double[] b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    public static double[] Cross(double[] a, double[] b) =>
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    public static double Dot(double[] a, double[] b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

    public static double[] Normalize(double[] v, MitsubaElement where, string zero)
    {
        double l = Math.Sqrt(Dot(v, v));
        if (!(l > 1e-12)) throw new InputException(where.Where, $"<{where.Tag}>: {zero}", "check the vectors");
        return [v[0] / l, v[1] / l, v[2] / l];
    }
}
