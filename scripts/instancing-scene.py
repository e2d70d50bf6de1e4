#!/usr/bin/env python3
"""Writes a pbrt-v4 scene of N ObjectInstances of one T-triangle mesh (a wavy grid), for measuring instancing.

Usage: scripts/instancing-scene.py OUT.pbrt [--instances 1000] [--rows 16]   (triangles = 2·rows·2·rows = 4·rows²; 16 → 1024)
Then e.g.: /usr/bin/time -v spectral render OUT.pbrt -o /tmp/out --width 32 --height 32 --spp 1
(peak working set = "Maximum resident set size"). Nothing is committed: the file is generated.
"""
import argparse, math

ap = argparse.ArgumentParser()
ap.add_argument("out")
ap.add_argument("--instances", type=int, default=1000)
ap.add_argument("--rows", type=int, default=16)
a = ap.parse_args()
n = 2 * a.rows   # n × a.rows quads, two triangles each: 4·rows² triangles
P, idx = [], []
for j in range(a.rows + 1):
    for i in range(n + 1):
        x, z = i / n - 0.5, j / a.rows - 0.5
        P += [x, 0.05 * math.sin(6 * x) * math.cos(5 * z), z]
for j in range(a.rows):
    for i in range(n):
        v = j * (n + 1) + i
        idx += [v, v + n + 1, v + 1, v + 1, v + n + 1, v + n + 2]
side = math.ceil(math.sqrt(a.instances))
with open(a.out, "w") as f:
    f.write('LookAt 0 30 30  0 0 0  0 1 0\nCamera "perspective" "float fov" [50]\n'
            'Film "rgb" "integer xresolution" [32] "integer yresolution" [32]\nSampler "independent" "integer pixelsamples" [1]\n'
            'WorldBegin\nLightSource "distant" "point3 from" [0 10 3] "point3 to" [0 0 0] "blackbody L" [5500]\n'
            'Material "diffuse"\nObjectBegin "tile"\n')
    f.write('Shape "trianglemesh" "point3 P" [' + " ".join(f"{v:.5g}" for v in P) + ']\n  "integer indices" ['
            + " ".join(map(str, idx)) + "]\nObjectEnd\n")
    for k in range(a.instances):
        x, z = k % side - side / 2, k // side - side / 2
        f.write(f'AttributeBegin\nTranslate {x * 1.1:.3f} 0 {z * 1.1:.3f}\nRotate {k * 37 % 360} 0 1 0\n'
                f'ObjectInstance "tile"\nAttributeEnd\n')
print(f"{a.out}: {a.instances} instances of {4 * a.rows * a.rows} triangles")
