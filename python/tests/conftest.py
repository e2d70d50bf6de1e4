"""Fixtures: the repository, libspectral (SPECTRAL_LIBRARY, else the package's bundled copy) and the CLI it is checked
against (SPECTRAL_CLI: a `spectral` executable or spectral.dll; default the Release build of src/SpectralRenderer.Cli)."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "python"))


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def sr():
    from spectralrenderer import _native
    path = _native._locate()
    if not path.exists():
        pytest.skip(f"no libspectral.so at {path}: publish it (scripts/build-wheel.sh) or set SPECTRAL_LIBRARY")
    import spectralrenderer
    return spectralrenderer


@pytest.fixture(scope="session")
def cli():
    """Runs `spectral ARGS…` (the command line under test's reference); returns the CompletedProcess."""
    exe = os.environ.get("SPECTRAL_CLI") or str(REPO / "src/SpectralRenderer.Cli/bin/Release/net10.0/spectral.dll")
    if not Path(exe).exists():
        pytest.skip(f"no CLI at {exe}: dotnet build SpectralRenderer.sln -c Release, or set SPECTRAL_CLI")
    prefix = [shutil.which("dotnet") or "dotnet", exe] if exe.endswith(".dll") else [exe]

    def run(*args):
        return subprocess.run(prefix + [str(a) for a in args], capture_output=True, text=True, cwd=REPO)
    return run


@pytest.fixture(scope="session")
def cli_chart_npy(cli, tmp_path_factory):
    """spectral.npy of `spectral render scenes/paper-3.1-colorchecker-d65.json` at the scene's own size (issue 28's bar)."""
    out = tmp_path_factory.mktemp("cli-chart") / "chart"
    p = cli("render", "scenes/paper-3.1-colorchecker-d65.json", "-o", out, "--formats", "npy", "--quiet")
    assert p.returncode == 0, p.stderr
    return out


def read_png(path):
    """(A file's or PNG bytes') An 8-bit grey or RGB or a 16-bit grey PNG's pixels as a NumPy array (H x W or H x W x 3):
    the five filter types, no interlace."""
    import struct
    import zlib
    import numpy as np
    data, pos, idat = path if isinstance(path, bytes) else Path(path).read_bytes(), 8, b""
    while pos < len(data):
        (length,), kind = struct.unpack(">I", data[pos:pos + 4]), data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    assert (depth, colour) in ((8, 0), (8, 2), (16, 0)), (depth, colour)
    bpp = 3 if colour == 2 else depth // 8
    stride, raw = w * bpp, zlib.decompress(idat)
    out, prior = np.zeros((h, stride), np.uint8), np.zeros(stride, np.int32)
    for y in range(h):
        ft, line = raw[y * (stride + 1)], np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        cur = np.zeros(stride, np.int32)
        for i in range(stride):
            a = cur[i - bpp] if i >= bpp else 0
            b, c = prior[i], prior[i - bpp] if i >= bpp else 0
            if ft == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else b if pb <= pc else c
            else:
                p = (0, a, b, (a + b) // 2)[ft]
            cur[i] = (line[i] + p) & 0xFF
        out[y], prior = cur, cur
    if depth == 16:   # big-endian samples
        return (out[:, 0::2].astype(np.uint16) << 8) | out[:, 1::2]
    return out.reshape(h, w) if bpp == 1 else out.reshape(h, w, 3)
