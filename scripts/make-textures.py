#!/usr/bin/env python3
"""Writes the small example textures of scenes/textures/ (issue 26) from the repository's own data, standard library only:

  colorchecker-ohta.img/.hdr  ENVI cube, 12 x 8 texels (2 x 2 per patch), the 24 Ohta reflectances of
                              data/colorchecker-ohta.csv every 10 nm over 380-780 nm (41 bands, float32 little-endian, BSQ)
  colorchecker-srgb.png       8-bit sRGB PNG, 24 x 16 pixels (4 x 4 per patch), the patches' sRGB codes from
                              data/reference/colorchecker-ohta-d65-2deg.csv (rendered through the sigmoid uplift)

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
per, w, h = 2, 12, 8
planes = bytearray()
for wl in wavelengths:
    for y in range(h):
        for x in range(w):
            patch = (y // per) * 6 + x // per
            planes += struct.pack("<f", table[float(wl)][patch])
(out / "colorchecker-ohta.img").write_bytes(bytes(planes))
(out / "colorchecker-ohta.hdr").write_text(
    "ENVI\ndescription = {ColorChecker, Ohta reflectances (data/colorchecker-ohta.csv), 2 x 2 texels per patch; scripts/make-textures.py}\n"
    f"samples = {w}\nlines = {h}\nbands = {len(wavelengths)}\nheader offset = 0\nfile type = ENVI Standard\ndata type = 4\n"
    "interleave = bsq\nbyte order = 0\nwavelength units = Nanometers\n"
    "wavelength = {" + ", ".join(str(v) for v in wavelengths) + "}\n")

# sRGB PNG
with open(root / "data" / "reference" / "colorchecker-ohta-d65-2deg.csv", newline="") as f:
    codes = [(int(r["srgb8_r"]), int(r["srgb8_g"]), int(r["srgb8_b"])) for r in csv.DictReader(f)]
per, w, h = 4, 24, 16
raw = bytearray()
for y in range(h):
    raw.append(0)  # filter: none
    for x in range(w):
        raw += bytes(codes[(y // per) * 6 + x // per])


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) + chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b"")
(out / "colorchecker-srgb.png").write_bytes(png)
print(f"wrote {out}/colorchecker-ohta.img/.hdr and colorchecker-srgb.png")
