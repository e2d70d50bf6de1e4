#!/usr/bin/env python3
"""Writes scenes/gltf/showcase.gltf (and tiles.jpg, with Debian's cjpeg): a small glTF 2.0 scene for `spectral render`.

A tiled floor (a baseline JPEG base-colour texture), a gold cube on a turned pedestal (a node hierarchy: T·R·S and a
child's matrix), a dispersive glass block (KHR_materials_transmission, _ior, _dispersion, _volume), an emissive panel
(KHR_materials_emissive_strength: 60 cd/m² at its warm white), a warm point light of 400 cd and a spot light of 1500 cd
(KHR_lights_punctual), and a perspective camera. The buffer is a base64 data: URI, so the .gltf is one file beside its
texture. Python's standard library only; run from anywhere: python3 scenes/gltf/make-showcase.py
"""
import base64, json, math, os, struct, subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
buf = bytearray()
accessors, views = [], []

def accessor(values, fmt, ctype, typ, count, minmax=False):
    while len(buf) % 4:
        buf.append(0)
    offset = len(buf)
    buf.extend(struct.pack("<" + fmt * len(values), *values))
    views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(buf) - offset})
    a = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": typ}
    if minmax:
        a["min"] = [min(values[i::3]) for i in range(3)]
        a["max"] = [max(values[i::3]) for i in range(3)]
    accessors.append(a)
    return len(accessors) - 1

meshes = []
def mesh(positions, normals, uvs, indices, material):
    prim = {"attributes": {"POSITION": accessor(positions, "f", 5126, "VEC3", len(positions) // 3, True),
                           "NORMAL": accessor(normals, "f", 5126, "VEC3", len(normals) // 3),
                           "TEXCOORD_0": accessor(uvs, "f", 5126, "VEC2", len(uvs) // 2)},
            "indices": accessor(indices, "H", 5123, "SCALAR", len(indices)), "material": material}
    meshes.append({"primitives": [prim]})
    return len(meshes) - 1

def square(sx, sy, repeat=1.0):
    """A rectangle in the xy plane facing +z; uv (0, 0) at its top-left corner."""
    hx, hy = sx / 2, sy / 2
    return ([-hx, hy, 0, hx, hy, 0, hx, -hy, 0, -hx, -hy, 0], [0, 0, 1] * 4,
            [0, 0, repeat, 0, repeat, repeat, 0, repeat], [0, 2, 1, 0, 3, 2])

def cube():
    """A unit cube centred at the origin: 6 faces of 4 vertices with their normals."""
    p, n, uv, idx = [], [], [], []
    for axis in range(3):
        for sign in (1, -1):
            normal = [0, 0, 0]; normal[axis] = sign
            u = [0, 0, 0]; u[(axis + 1) % 3] = 1
            v = [0, 0, 0]; v[(axis + 2) % 3] = 1
            if sign < 0:
                u = [-c for c in u]
            base = len(p) // 3
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p += [0.5 * (normal[i] + a * u[i] + b * v[i]) for i in range(3)]
                n += normal
                uv += [(a + 1) / 2, (1 - b) / 2]
            idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return p, n, uv, idx

def towards(frm, to):
    """The shortest-arc rotation turning the node's −Z (where glTF lights and cameras look) from frm towards to."""
    b = [t - f for t, f in zip(to, frm)]
    l = math.sqrt(sum(c * c for c in b)); b = [c / l for c in b]
    a = [0, 0, -1]
    axis = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    q = axis + [1 + sum(x * y for x, y in zip(a, b))]
    n = math.sqrt(sum(c * c for c in q))
    return [round(c / n, 6) for c in q]

def quat(axis, degrees):
    s = math.sin(math.radians(degrees) / 2)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(math.radians(degrees) / 2)]

materials = [
    {"name": "tiles", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 0.7}},
    {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.766, 0.336, 1], "metallicFactor": 1.0, "roughnessFactor": 0.3}},
    {"name": "pedestal", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0.0, "roughnessFactor": 0.4}},
    {"name": "glass", "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.0},
     "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.5168},
                    "KHR_materials_dispersion": {"dispersion": round(20 / 30.0, 6)},
                    "KHR_materials_volume": {"thicknessFactor": 0.8}}},
    {"name": "panel", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
     "emissiveFactor": [1.0, 0.9, 0.75], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 60.0}}},
]
floor = mesh(*square(6, 6, 3), 0)
gold_cube = mesh(*cube(), 1)
pedestal = mesh(*cube(), 2)
glass = mesh(*cube(), 3)
panel = mesh(*square(1.6, 0.5), 4)

nodes = [
    {"name": "floor", "mesh": floor, "rotation": quat([1, 0, 0], -90)},
    {"name": "pedestal", "mesh": pedestal, "translation": [-0.9, 0.3, 0], "rotation": quat([0, 1, 0], 30),
     "scale": [0.9, 0.6, 0.9], "children": [2]},
    # The gold cube sits on the pedestal: its matrix (column-major) in the pedestal's frame, undoing the pedestal's y scale.
    {"name": "gold", "mesh": gold_cube, "matrix": [0.6, 0, 0, 0, 0, 0.9, 0, 0, 0, 0, 0.6, 0, 0, 0.95, 0, 1]},
    {"name": "glass", "mesh": glass, "translation": [0.9, 0.45, 0.4], "rotation": quat([0, 1, 0], -20), "scale": [0.9, 0.9, 0.9]},
    {"name": "panel", "mesh": panel, "translation": [0, 2.2, -2.2], "rotation": quat([1, 0, 0], 25)},
    {"name": "lamp", "translation": [2.0, 3.0, 2.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "spot", "translation": [-2.0, 3.5, 1.5], "extensions": {"KHR_lights_punctual": {"light": 1}},
     "rotation": towards([-2.0, 3.5, 1.5], [0, 0.3, 0])},
    {"name": "camera", "camera": 0, "translation": [0, 1.6, 5.2], "rotation": quat([1, 0, 0], -11)},
]
gltf = {
    "asset": {"version": "2.0", "generator": "SpectralRenderer scenes/gltf/make-showcase.py"},
    "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_dispersion",
                       "KHR_materials_volume", "KHR_materials_emissive_strength"],
    "scene": 0,
    "scenes": [{"name": "showcase", "nodes": [0, 1, 3, 4, 5, 6, 7]}],
    "nodes": nodes,
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 4 / 3, "znear": 0.05}}],
    "extensions": {"KHR_lights_punctual": {"lights": [
        {"name": "warm lamp", "type": "point", "color": [1.0, 0.85, 0.7], "intensity": 400.0},
        {"name": "spot", "type": "spot", "color": [1.0, 1.0, 1.0], "intensity": 1500.0,
         "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.45}}]}},
    "materials": materials,
    "meshes": meshes,
    "textures": [{"source": 0, "sampler": 0}],
    "samplers": [{"wrapS": 10497, "wrapT": 10497}],
    "images": [{"uri": "tiles.jpg"}],
    "accessors": accessors,
    "bufferViews": views,
    "buffers": [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}],
}
with open(os.path.join(HERE, "showcase.gltf"), "w") as f:
    json.dump(gltf, f, indent=1)
    f.write("\n")

# The floor's texture: 64 × 64 terracotta and sand tiles with grout lines, a baseline 4:2:0 JPEG.
w = h = 64
pixels = bytearray()
for y in range(h):
    for x in range(w):
        grout = x % 32 < 2 or y % 32 < 2
        tile = ((x // 32) + (y // 32)) % 2
        c = (200, 195, 185) if grout else (176, 92, 60) if tile else (214, 190, 140)
        shade = 8 * math.sin(x * 0.7) * math.cos(y * 0.5)
        pixels += bytes(max(0, min(255, int(v + shade))) for v in c)
ppm = os.path.join(HERE, "tiles.ppm")
with open(ppm, "wb") as f:
    f.write(b"P6\n%d %d\n255\n" % (w, h) + bytes(pixels))
try:
    subprocess.run(["cjpeg", "-quality", "90", "-baseline", "-outfile", os.path.join(HERE, "tiles.jpg"), ppm], check=True)
finally:
    os.remove(ppm)
print("wrote showcase.gltf and tiles.jpg")
