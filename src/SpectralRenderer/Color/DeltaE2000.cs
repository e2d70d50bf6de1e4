namespace SpectralRenderer.Color;

/// <summary>
/// The CIEDE2000 colour difference (CIE 142-2001), implemented as in Sharma, Wu &amp; Dalal (2005),
/// "The CIEDE2000 colour-difference formula: implementation notes", with k_L = k_C = k_H = 1.
/// </summary>
public static class DeltaE2000
{
    static double Deg(double rad) => rad * 180 / Math.PI;
    static double Rad(double deg) => deg * Math.PI / 180;

    public static double Between(Lab lab1, Lab lab2)
    {
        double c1 = lab1.Chroma, c2 = lab2.Chroma;
        double cBar = (c1 + c2) / 2;
        double c7 = Math.Pow(cBar, 7);
        double g = 0.5 * (1 - Math.Sqrt(c7 / (c7 + Math.Pow(25, 7))));
        double a1p = (1 + g) * lab1.A, a2p = (1 + g) * lab2.A;
        double c1p = Math.Sqrt(a1p * a1p + lab1.B * lab1.B);
        double c2p = Math.Sqrt(a2p * a2p + lab2.B * lab2.B);
        double h1p = HueAngle(lab1.B, a1p), h2p = HueAngle(lab2.B, a2p);

        double dLp = lab2.L - lab1.L;
        double dCp = c2p - c1p;
        double dhp;
        if (c1p * c2p == 0) dhp = 0;
        else if (Math.Abs(h2p - h1p) <= 180) dhp = h2p - h1p;
        else if (h2p - h1p > 180) dhp = h2p - h1p - 360;
        else dhp = h2p - h1p + 360;
        double dHp = 2 * Math.Sqrt(c1p * c2p) * Math.Sin(Rad(dhp / 2));

        double lBarP = (lab1.L + lab2.L) / 2;
        double cBarP = (c1p + c2p) / 2;
        double hBarP;
        if (c1p * c2p == 0) hBarP = h1p + h2p;
        else if (Math.Abs(h1p - h2p) <= 180) hBarP = (h1p + h2p) / 2;
        else if (h1p + h2p < 360) hBarP = (h1p + h2p + 360) / 2;
        else hBarP = (h1p + h2p - 360) / 2;

        double t = 1 - 0.17 * Math.Cos(Rad(hBarP - 30)) + 0.24 * Math.Cos(Rad(2 * hBarP))
                     + 0.32 * Math.Cos(Rad(3 * hBarP + 6)) - 0.20 * Math.Cos(Rad(4 * hBarP - 63));
        double dTheta = 30 * Math.Exp(-Math.Pow((hBarP - 275) / 25, 2));
        double cBarP7 = Math.Pow(cBarP, 7);
        double rc = 2 * Math.Sqrt(cBarP7 / (cBarP7 + Math.Pow(25, 7)));
        double l50 = (lBarP - 50) * (lBarP - 50);
        double sl = 1 + 0.015 * l50 / Math.Sqrt(20 + l50);
        double sc = 1 + 0.045 * cBarP;
        double sh = 1 + 0.015 * cBarP * t;
        double rt = -Math.Sin(Rad(2 * dTheta)) * rc;

        double tl = dLp / sl, tc = dCp / sc, th = dHp / sh;
        return Math.Sqrt(tl * tl + tc * tc + th * th + rt * tc * th);
    }

    static double HueAngle(double b, double ap)
    {
        if (b == 0 && ap == 0) return 0;
        double h = Deg(Math.Atan2(b, ap));
        return h < 0 ? h + 360 : h;
    }
}
