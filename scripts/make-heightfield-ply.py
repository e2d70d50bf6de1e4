#!/usr/bin/env python3
"""Writes a large heightfield mesh as a binary PLY (and a path scene that renders it), for BVH build time and memory.

    usage: scripts/make-heightfield-ply.py OUT_DIR [N]     (N × N vertices, 2 (N − 1)² triangles; default N = 2830: 16.0 M)

A grid over [0, 1]² with z = a sum of sines (smooth hills, no two triangles coplanar across the field), indexed: each
vertex stored once. Writes OUT_DIR/heightfield.ply and OUT_DIR/heightfield.json (the path integrator, a daylight sky).
The file is large (16 M triangles: ~300 MB): keep it in /tmp, never in the repository. Standard library only.
"""
import math
import os
import struct
import sys
from array import array


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out, n = sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 2830
    os.makedirs(out, exist_ok=True)
    faces = 2 * (n - 1) ** 2
    ply = os.path.join(out, "heightfield.ply")
    with open(ply, "wb") as f:
        f.write((f"ply\nformat binary_little_endian 1.0\ncomment heightfield {n}x{n}, scripts/make-heightfield-ply.py\n"
                 f"element vertex {n * n}\nproperty float x\nproperty float y\nproperty float z\n"
                 f"element face {faces}\nproperty list uchar int vertex_indices\nend_header\n").encode("ascii"))
        for j in range(n):
            y = j / (n - 1)
            row = array("f")
            for i in range(n):
                x = i / (n - 1)
                z = 0.05 * (math.sin(17 * x) * math.cos(13 * y) + 0.5 * math.sin(41 * x + 29 * y))
                row.extend((x, z, y))
            if sys.byteorder != "little":
                row.byteswap()
            f.write(row.tobytes())
        three = struct.pack("<B", 3)
        for j in range(n - 1):
            block = bytearray()
            for i in range(n - 1):
                a = j * n + i
                block += three + struct.pack("<3i", a, a + n, a + 1)
                block += three + struct.pack("<3i", a + 1, a + n, a + n + 1)
            f.write(block)
    scene = os.path.join(out, "heightfield.json")
    with open(scene, "w") as f:
        f.write("""{
  "name": "heightfield",
  "bands": "380:780:20",
  "radiometry": "physical",
  "integrator": "path",
  "camera": { "position": [0.5, 0.6, -0.4], "look_at": [0.5, 0, 0.5], "fov": 50, "width": 160, "height": 120, "spp": 4 },
  "sky": { "type": "daylight", "cct": 6504, "luminance": 5000 },
  "materials": { "ground": { "type": "lambertian", "reflectance": 0.5 } },
  "objects": [ { "type": "mesh", "name": "field", "file": "heightfield.ply", "material": "ground" } ]
}
""")
    print(f"{ply}: {n * n} vertices, {faces} triangles; scene {scene}")


if __name__ == "__main__":
    main()
