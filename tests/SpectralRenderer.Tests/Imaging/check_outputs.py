#!/usr/bin/env python3
"""Independent reader for the interop tests: parses our .npy header and decodes our PNGs
using only the standard library (struct, zlib, json). Usage: check_outputs.py manifest.json"""
import json, struct, sys, zlib

def check_npy(spec):
    with open(spec["path"], "rb") as f:
        data = f.read()
    assert data[:6] == b"\x93NUMPY", "bad magic"
    assert data[6:8] == b"\x01\x00", "not version 1.0"
    (hlen,) = struct.unpack("<H", data[8:10])
    assert (10 + hlen) % 64 == 0, "header not padded to 64 bytes"
    header = data[10:10 + hlen].decode("latin1")
    assert header.endswith("\n"), "header does not end in a newline"
    d = eval(header, {"__builtins__": {}}, {"True": True, "False": False})
    assert d["descr"] == "<f4", d["descr"]
    assert d["fortran_order"] is False
    assert list(d["shape"]) == spec["shape"], (d["shape"], spec["shape"])
    h, w, n = d["shape"]
    body = data[10 + hlen:]
    assert len(body) == h * w * n * 4, "data size"
    for y, x, b, bits in spec["values"]:
        (got,) = struct.unpack_from("<I", body, 4 * ((y * w + x) * n + b))
        assert got == bits, f"npy[{y},{x},{b}] bits {got:#x} != {bits:#x}"
    print(f"npy ok: shape {d['shape']} dtype {d['descr']}, {len(spec['values'])} values")

def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c

def decode_png(path):
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "bad signature"
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        ctype = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        (crc,) = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        assert crc == zlib.crc32(ctype + body) & 0xffffffff, f"CRC of {ctype}"
        if ctype == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif ctype == b"IDAT":
            idat += body
        elif ctype == b"IEND":
            break
        pos += 12 + length
    width, height, depth, colour, comp, filt, interlace = ihdr
    assert (comp, filt, interlace) == (0, 0, 0)
    channels = {0: 1, 2: 3}[colour]
    bpp = channels * depth // 8
    stride = width * bpp
    raw = zlib.decompress(idat)
    assert len(raw) == height * (stride + 1), "inflated size"
    out, prior, filters = bytearray(), bytearray(stride), set()
    for y in range(height):
        ft = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        filters.add(ft)
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prior[i]
            c = prior[i - bpp] if i >= bpp else 0
            if ft == 0: p = 0
            elif ft == 1: p = a
            elif ft == 2: p = b
            elif ft == 3: p = (a + b) // 2
            elif ft == 4: p = paeth(a, b, c)
            else: raise AssertionError(f"filter type {ft}")
            line[i] = (line[i] + p) & 0xff
        out += line
        prior = line
    if depth == 16:
        samples = list(struct.unpack(f">{len(out) // 2}H", bytes(out)))
    else:
        samples = list(out)
    return (width, height, depth, colour), samples, filters

def main():
    with open(sys.argv[1]) as f:
        manifest = json.load(f)
    check_npy(manifest["npy"])
    seen = set()
    for png in manifest["pngs"]:
        info, samples, filters = decode_png(png["path"])
        assert list(info) == [png["width"], png["height"], png["depth"], png["colour"]], (info, png)
        assert samples == png["samples"], f"{png['path']}: samples differ"
        seen |= filters
        print(f"png ok: {png['path'].split('/')[-1]} {info} filters {sorted(filters)}")
    print("filters seen: " + ",".join(str(f) for f in sorted(seen)))

main()
