"""docs/python-example.py runs (tiny images, one scene per section): the parts whose inputs are missing say why."""
import os
import subprocess
import sys


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
