#!/usr/bin/env python3
"""Writes the small example textures of scenes/textures/ (issue 26) from the repository's own data, standard library only:

  colorchecker-ohta.img/.hdr  ENVI cube, 48 x 32 texels (8 x 8 per patch: 6 x 6 of the patch inside a 1-texel frame), the
                              24 Ohta reflectances of data/colorchecker-ohta.csv every 10 nm over 380-780 nm (41 bands,
                              float32 little-endian, BSQ); the chart's black frame is patch 24 (black 2) of the same table
  colorchecker-srgb.png       8-bit sRGB PNG, 96 x 64 pixels (16 x 16 per patch: 12 x 12 inside a 2-pixel frame), the
                              patches' sRGB codes from data/reference/colorchecker-ohta-d65-2deg.csv (rendered through the
                              sigmoid uplift), the frame patch 24's code

Run from the repository root: python3 scripts/make-textures.py
"""
import csv
import struct
import zlib
from pathlib import Path

root = Path(__file__).resolve().parent.parent
out = root / "scenes" / "textures"
out.mkdir(parents=True, exist_ok=True)

# ENVI cube
with open(root / "data" / "colorchecker-ohta.csv", newline="") as f:
    rows = [r for r in csv.reader(f) if r and r[0][0].isdigit()]
table = {float(r[0]): [float(v) for v in r[1:25]] for r in rows}
wavelengths = [380 + 10 * i for i in range(41)]


def cell(x, y, per, frame):
    """The patch (0-23) at texel (x, y) of a chart of per x per texel cells, or 23 (black 2) in a cell's frame."""
    u, v = x % per, y % per
    inside = frame <= u < per - frame and frame <= v < per - frame
    return (y // per) * 6 + x // per if inside else 23


per, w, h = 8, 48, 32
planes = bytearray()
for wl in wavelengths:
    for y in range(h):
        for x in range(w):
            patch = cell(x, y, per, 1)
            planes += struct.pack("<f", table[float(wl)][patch])
(out / "colorchecker-ohta.img").write_bytes(bytes(planes))
(out / "colorchecker-ohta.hdr").write_text(
    "ENVI\ndescription = {ColorChecker, Ohta reflectances (data/colorchecker-ohta.csv), 8 x 8 texels per patch in a black-2 frame; scripts/make-textures.py}\n"
    f"samples = {w}\nlines = {h}\nbands = {len(wavelengths)}\nheader offset = 0\nfile type = ENVI Standard\ndata type = 4\n"
    "interleave = bsq\nbyte order = 0\nwavelength units = Nanometers\n"
    "wavelength = {" + ", ".join(str(v) for v in wavelengths) + "}\n")

# sRGB PNG
with open(root / "data" / "reference" / "colorchecker-ohta-d65-2deg.csv", newline="") as f:
    codes = [(int(r["srgb8_r"]), int(r["srgb8_g"]), int(r["srgb8_b"])) for r in csv.DictReader(f)]
per, w, h = 16, 96, 64
raw = bytearray()
for y in range(h):
    raw.append(0)  # filter: none
    for x in range(w):
        raw += bytes(codes[cell(x, y, per, 2)])


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) + chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b"")
(out / "colorchecker-srgb.png").write_bytes(png)
print(f"wrote {out}/colorchecker-ohta.img/.hdr and colorchecker-srgb.png")
