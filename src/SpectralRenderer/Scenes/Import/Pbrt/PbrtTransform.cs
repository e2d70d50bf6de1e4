namespace SpectralRenderer.Scenes.Import.Pbrt;

/// <summary>
/// A 4 × 4 affine transform in double precision, row-major, acting on column vectors (p' = M·p), as pbrt-v4's
/// `Transform` (pbrt-v4 src/pbrt/util/transform.h): the graphics state's current transformation matrix and its directives.
/// </summary>
public readonly struct PbrtTransform
{
    readonly double[] _m;

    PbrtTransform(double[] m) => _m = m;

    public static PbrtTransform Identity => new([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);

    public double this[int row, int column] => (_m ?? Identity._m)[row * 4 + column];

    /// <summary>The 16 numbers row by row.</summary>
    public double[] RowMajor => (double[])(_m ?? Identity._m).Clone();

    public static PbrtTransform FromRowMajor(ReadOnlySpan<double> m)
    {
        if (m.Length != 16) throw new ArgumentException("a 4 × 4 matrix has 16 numbers", nameof(m));
        return new(m.ToArray());
    }

    /// <summary>pbrt's `Transform`/`ConcatTransform` list the matrix column by column (the translation is 12, 13, 14).</summary>
    public static PbrtTransform FromPbrtList(ReadOnlySpan<double> m)
    {
        var r = new double[16];
        for (int row = 0; row < 4; row++)
            for (int column = 0; column < 4; column++) r[row * 4 + column] = m[column * 4 + row];
        return new(r);
    }

    public static PbrtTransform operator *(PbrtTransform a, PbrtTransform b)
    {
        var r = new double[16];
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++)
            {
                double s = 0;
                for (int k = 0; k < 4; k++) s += a[i, k] * b[k, j];
                r[i * 4 + j] = s;
            }
        return new(r);
    }

    public static PbrtTransform Translate(double x, double y, double z) => new([1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z, 0, 0, 0, 1]);

    public static PbrtTransform Scale(double x, double y, double z) => new([x, 0, 0, 0, 0, y, 0, 0, 0, 0, z, 0, 0, 0, 0, 1]);

    /// <summary>A rotation by <paramref name="degrees"/> about the axis (right-handed: counter-clockwise looking down the axis).</summary>
    public static PbrtTransform Rotate(double degrees, double ax, double ay, double az)
    {
        double len = Math.Sqrt(ax * ax + ay * ay + az * az);
        if (!(len > 0)) return Identity;
        double x = ax / len, y = ay / len, z = az / len;
        double t = degrees * Math.PI / 180, s = Math.Sin(t), c = Math.Cos(t);
        return new([
            x * x + (1 - x * x) * c, x * y * (1 - c) - z * s, x * z * (1 - c) + y * s, 0,
            x * y * (1 - c) + z * s, y * y + (1 - y * y) * c, y * z * (1 - c) - x * s, 0,
            x * z * (1 - c) - y * s, y * z * (1 - c) + x * s, z * z + (1 - z * z) * c, 0,
            0, 0, 0, 1]);
    }

    /// <summary>
    /// pbrt's LookAt: camera-from-world for an eye at <paramref name="eye"/> looking at <paramref name="look"/>; the
    /// camera's +z is the viewing direction d, its +x is normalize(up) × d and its +y is d × x (pbrt-v4 transform.cpp).
    /// Null when the eye is the look point or up is parallel to the viewing direction.
    /// </summary>
    public static PbrtTransform? LookAt(ReadOnlySpan<double> eye, ReadOnlySpan<double> look, ReadOnlySpan<double> up)
    {
        double[] d = Normalize([look[0] - eye[0], look[1] - eye[1], look[2] - eye[2]]);
        double[] u = Normalize([up[0], up[1], up[2]]);
        if (d.Length == 0 || u.Length == 0) return null;
        double[] right = Cross(u, d);
        if (!(Math.Sqrt(Dot(right, right)) > 1e-12)) return null;
        right = Normalize(right);
        double[] newUp = Cross(d, right);
        var worldFromCamera = new PbrtTransform([
            right[0], newUp[0], d[0], eye[0],
            right[1], newUp[1], d[1], eye[1],
            right[2], newUp[2], d[2], eye[2],
            0, 0, 0, 1]);
        return worldFromCamera.Inverse();
    }

    public double[] Point(double x, double y, double z)
    {
        double w = this[3, 0] * x + this[3, 1] * y + this[3, 2] * z + this[3, 3];
        return [(this[0, 0] * x + this[0, 1] * y + this[0, 2] * z + this[0, 3]) / w,
            (this[1, 0] * x + this[1, 1] * y + this[1, 2] * z + this[1, 3]) / w,
            (this[2, 0] * x + this[2, 1] * y + this[2, 2] * z + this[2, 3]) / w];
    }

    public double[] Vector(double x, double y, double z) =>
        [this[0, 0] * x + this[0, 1] * y + this[0, 2] * z,
            this[1, 0] * x + this[1, 1] * y + this[1, 2] * z,
            this[2, 0] * x + this[2, 1] * y + this[2, 2] * z];

    /// <summary>The determinant of the upper 3 × 3: negative when the transform swaps handedness.</summary>
    public double Determinant3 =>
        this[0, 0] * (this[1, 1] * this[2, 2] - this[1, 2] * this[2, 1])
        - this[0, 1] * (this[1, 0] * this[2, 2] - this[1, 2] * this[2, 0])
        + this[0, 2] * (this[1, 0] * this[2, 1] - this[1, 1] * this[2, 0]);

    public bool IsAffine => this[3, 0] == 0 && this[3, 1] == 0 && this[3, 2] == 0 && this[3, 3] == 1;

    /// <summary>The inverse (Gauss–Jordan with partial pivoting), or null for a singular matrix.</summary>
    public PbrtTransform? Inverse()
    {
        var a = RowMajor;
        var inv = Identity.RowMajor;
        for (int col = 0; col < 4; col++)
        {
            int pivot = col;
            for (int r = col + 1; r < 4; r++)
                if (Math.Abs(a[r * 4 + col]) > Math.Abs(a[pivot * 4 + col])) pivot = r;
            if (!(Math.Abs(a[pivot * 4 + col]) > 1e-300)) return null;
            if (pivot != col)
                for (int k = 0; k < 4; k++)
                {
                    (a[col * 4 + k], a[pivot * 4 + k]) = (a[pivot * 4 + k], a[col * 4 + k]);
                    (inv[col * 4 + k], inv[pivot * 4 + k]) = (inv[pivot * 4 + k], inv[col * 4 + k]);
                }
            double p = a[col * 4 + col];
            for (int k = 0; k < 4; k++) { a[col * 4 + k] /= p; inv[col * 4 + k] /= p; }
            for (int r = 0; r < 4; r++)
            {
                if (r == col) continue;
                double f = a[r * 4 + col];
                if (f == 0) continue;
                for (int k = 0; k < 4; k++) { a[r * 4 + k] -= f * a[col * 4 + k]; inv[r * 4 + k] -= f * inv[col * 4 + k]; }
            }
        }
        foreach (double v in inv)
            if (!double.IsFinite(v)) return null;
        return new(inv);
    }

    internal static double Dot(double[] a, double[] b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

    internal static double[] Cross(double[] a, double[] b) =>
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];

    /// <summary>The unit vector, or an empty array for a zero or non-finite one.</summary>
    internal static double[] Normalize(double[] v)
    {
        double len = Math.Sqrt(Dot(v, v));
        return len > 0 && double.IsFinite(len) ? [v[0] / len, v[1] / len, v[2] / len] : [];
    }
}
