#!/usr/bin/env python3
"""Writes scenes/oba-paper-matrix.csv: the re-radiation (Donaldson) matrix of an optically brightened paper.

Modelled, not measured (the same shapes as tests/.../Rendering/FluorescenceTests.cs, on 10 nm cells 300-780 nm):
  pulp reflectance  R0(l) = 0.88 - 0.10 g(l; 400, 35)            (slightly yellow: absorbs towards the blue)
  OBA absorption    a(l)  = 0.9 g(l; 365, 15)                    (excitation 340-400 nm)
  emission          p_o   = g(l_o; 440, 18) / sum                 (photon distribution, peak 440 nm)
  D[i,i] = R0(l_i) (1 - a(l_i));  D[o,i] = q a(l_i) l_i p_o / l_o for l_o > l_i, quantum yield q = 0.8
with g(x; mu, s) = exp(-(x - mu)^2 / (2 s^2)). Layout: docs/scene-format.md, "Fluorescence".
Usage: python3 scripts/oba-paper-matrix.py [output.csv]
"""
import math
import sys


def g(x, mu, s):
    return math.exp(-0.5 * (x - mu) ** 2 / (s * s))


def matrix(step=10.0, first=305.0, last=775.0, q=0.8, strength=0.9):
    cells = [first + step * j for j in range(int(round((last - first) / step)) + 1)]
    p = [g(l, 440, 18) for l in cells]
    total = sum(p)
    n = len(cells)
    d = [[0.0] * n for _ in range(n)]
    for i, li in enumerate(cells):
        a = strength * g(li, 365, 15)
        d[i][i] = (0.88 - 0.10 * g(li, 400, 35)) * (1 - a)
        for o, lo in enumerate(cells):
            if lo > li:
                d[o][i] = q * a * li * (p[o] / total) / lo
    return cells, d


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/oba-paper-matrix.csv"
    cells, d = matrix()
    fmt = lambda v: "0" if v < 1e-12 else f"{v:.6g}"
    with open(out, "w", newline="\n") as f:
        f.write("emission_nm," + ",".join(f"{l:g}" for l in cells) + "\n")
        for o, lo in enumerate(cells):
            f.write(f"{lo:g}," + ",".join(fmt(v) for v in d[o]) + "\n")


if __name__ == "__main__":
    main()
