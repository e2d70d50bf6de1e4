"""docs/python-example.py runs (tiny images, one scene per section): the parts whose inputs are missing say why."""
import os
import subprocess
import sys

import pytest


def test_the_example_script_runs(sr, repo, tmp_path):
    out = tmp_path / "example"
    p = subprocess.run([sys.executable, str(repo / "docs/python-example.py"), "--quick", "--out", str(out)],
                       capture_output=True, text=True, env={**os.environ, "PYTHONPATH": str(repo / "python")})
    assert p.returncode == 0, p.stderr
    for line in p.stdout.splitlines():
        if line.startswith("skipped:"):
            print(line)   # pytest -rP shows why (no meshes, no Matplotlib)
    rows = (out / "chromaticities.csv").read_text().splitlines()
    assert rows[0] == "kelvin,x,y" and len(rows) == 8
    # Warmer light, redder patch: x falls as the blackbody's temperature rises (Planckian locus, 2000 → 10000 K).
    xs = [float(r.split(",")[1]) for r in rows[1:]]
    assert all(a > b for a, b in zip(xs, xs[1:])), xs
    models = os.environ.get("SPECTRAL_MODELS")
    if models and os.path.exists(os.path.join(models, "stanford-bunny.obj")):
        assert (out / "bunny-05.png").read_bytes().startswith(b"\x89PNG")


def test_the_example_uses_colour_science_for_the_cie_1931_chromaticities_when_present(sr, repo, tmp_path):
    """With colour-science (SPECTRAL_ANCHORS_PYTHON: a Python importing colour, e.g. a venv made with
    --system-site-packages from ../shared/anchors/wheels), x, y are colour.XYZ_to_xy's and, with Matplotlib, the plot is
    colour's CIE 1931 chromaticity diagram."""
    py = os.environ.get("SPECTRAL_ANCHORS_PYTHON")
    probe = "import colour, numpy; import importlib.util as u; print(bool(u.find_spec('matplotlib')))"
    has = subprocess.run([py, "-c", probe], capture_output=True, text=True) if py else None
    if not has or has.returncode != 0:
        pytest.skip("no Python with colour-science: set SPECTRAL_ANCHORS_PYTHON (a venv from ../shared/anchors/wheels)")
    out = tmp_path / "example"
    p = subprocess.run([py, str(repo / "docs/python-example.py"), "--quick", "--out", str(out)], capture_output=True,
                       text=True, env={**os.environ, "PYTHONPATH": str(repo / "python")})
    assert p.returncode == 0, p.stderr
    assert "colour-science not installed" not in p.stdout and (out / "chromaticities.csv").exists()
    if has.stdout.strip() == "True":
        assert (out / "chromaticities.png").read_bytes().startswith(b"\x89PNG")
