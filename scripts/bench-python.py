#!/usr/bin/env python3
"""The Python package's overhead (issue 28's bar): the §3.2 bunny rendered from Python against `spectral render`.

    SPECTRAL_LIBRARY=DIR/libspectral.so SPECTRAL_CLI=PATH/spectral[.dll] python3 scripts/bench-python.py [ROUNDS] [SIZE]

Interleaved rounds (CLI, then Python, in each), so a busy machine's load falls on both alike. Reported per side, as the
median of the rounds: the render time (render.json's timings_s.render — the CLI's from its folder, Python's from the
manifest in memory) and the wall time (the CLI's whole process, writing only spectral.npy; Python's sr.render call).
The import time of the package (loading libspectral) is stated apart.
"""
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

repo = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(repo / "python"))
rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
size = int(sys.argv[2]) if len(sys.argv) > 2 else 512
scene = repo / "scenes/paper-3.2-bunny-05.json"
os.environ.setdefault("SPECTRAL_MODELS", str(repo.parent / "shared/models"))
cli = os.environ.get("SPECTRAL_CLI") or str(repo / "src/SpectralRenderer.Cli/bin/Release/net10.0/spectral.dll")
prefix = ["dotnet", cli] if cli.endswith(".dll") else [cli]

t = time.perf_counter()
import spectralrenderer as sr  # noqa: E402
sr.abi_version()               # loads the library
import_s = time.perf_counter() - t

cli_render, cli_wall, py_render, py_wall = [], [], [], []
with tempfile.TemporaryDirectory() as tmp:
    for i in range(rounds):
        out = Path(tmp) / f"cli{i}"
        t = time.perf_counter()
        subprocess.run(prefix + ["render", str(scene), "-o", str(out), "--width", str(size), "--height", str(size),
                                 "--formats", "npy", "--quiet"], check=True)
        cli_wall.append(time.perf_counter() - t)
        cli_render.append(json.loads((out / "render.json").read_text())["timings_s"]["render"])
        shutil.rmtree(out)
        t = time.perf_counter()
        r = sr.render(scene, width=size, height=size, formats="npy")
        py_wall.append(time.perf_counter() - t)
        py_render.append(r.manifest["timings_s"]["render"])
        del r

med = statistics.median
print(f"bunny {size}x{size}, {rounds} interleaved rounds, CLI {cli}")
print(f"render time (timings_s.render): CLI {med(cli_render):.3f} s, Python {med(py_render):.3f} s, "
      f"ratio {med(py_render) / med(cli_render):.3f}")
print(f"wall time: CLI process {med(cli_wall):.3f} s, sr.render {med(py_wall):.3f} s, ratio {med(py_wall) / med(cli_wall):.3f}")
print(f"import spectralrenderer + loading libspectral: {import_s:.3f} s")
