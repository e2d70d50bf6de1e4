using System.Text.Json.Nodes;

namespace SpectralRenderer.Scenes.Import.Gltf;

/// <summary>4×4 affine matrices as 16 doubles, row-major, acting on column vectors (p' = M·p): our scene's "matrix" layout.</summary>
static class Affine
{
    public static double[] Identity => RowMajorMatrix.Identity;

    public static double[] Multiply(double[] a, double[] b) => RowMajorMatrix.Multiply(a, b);

    /// <summary>T·R·S (glTF 2.0 §3.5.3): translation t, unit quaternion q = [x, y, z, w], scale s.</summary>
    public static double[] Trs(double[] t, double[] q, double[] s)
    {
        double x = q[0], y = q[1], z = q[2], w = q[3];
        // The rotation matrix of a unit quaternion (Shoemake 1985), columns scaled by s.
        double[] r =
        [
            1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
            2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
            2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y),
        ];
        return
        [
            r[0] * s[0], r[1] * s[1], r[2] * s[2], t[0],
            r[3] * s[0], r[4] * s[1], r[5] * s[2], t[1],
            r[6] * s[0], r[7] * s[1], r[8] * s[2], t[2],
            0, 0, 0, 1,
        ];
    }

    public static double[] Point(double[] m, double x, double y, double z) =>
        [m[0] * x + m[1] * y + m[2] * z + m[3], m[4] * x + m[5] * y + m[6] * z + m[7], m[8] * x + m[9] * y + m[10] * z + m[11]];

    public static double[] Direction(double[] m, double x, double y, double z) =>
        [m[0] * x + m[1] * y + m[2] * z, m[4] * x + m[5] * y + m[6] * z, m[8] * x + m[9] * y + m[10] * z];

    public static double[] Normalized(double[] v)
    {
        double l = Math.Sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        return l > 0 ? [v[0] / l, v[1] / l, v[2] / l] : v;
    }

    /// <summary>The determinant of the upper-left 3×3 (negative: the transform mirrors).</summary>
    public static double Determinant(double[] m) =>
        m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) + m[2] * (m[4] * m[9] - m[5] * m[8]);

    public static bool IsIdentity(double[] m)
    {
        var id = Identity;
        for (int i = 0; i < 16; i++)
            if (Math.Abs(m[i] - id[i]) > 1e-12) return false;
        return true;
    }

    public static JsonArray Json(double[] m) => [.. m.Select(v => (JsonNode)JsonValue.Create(GltfConverter.Round(v)))];
}
