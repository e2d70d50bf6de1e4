"""README, "Python": the package snippet runs as written (in a scratch folder holding the repository's scenes/), and
what it saved is the folder the CLI reads back: render.json's size and bands equal the arrays the snippet held."""
import json
import os
import re
import subprocess
import sys


def test_readme_package_snippet_runs_as_written(sr, repo, tmp_path):
    readme = (repo / "README.md").read_text(encoding="utf-8")
    section = readme[readme.index("\n## Python\n"):]
    snippet = re.search(r"^```python\n(.*?)^```", section, re.M | re.S).group(1)
    assert "sr.render(" in snippet
    (tmp_path / "scenes").symlink_to(repo / "scenes")
    probe = "\nprint('SHAPE', *r.cube.shape, len(r.wavelengths), *r.xyz.shape, *r.ids.shape)\n"
    env = {**os.environ, "PYTHONPATH": str(repo / "python")}
    done = subprocess.run([sys.executable, "-c", snippet + probe], cwd=tmp_path, capture_output=True, text=True, env=env)
    assert done.returncode == 0, done.stderr
    h, w, n, n2, h2, w2, c, h3, w3 = map(int, next(l for l in done.stdout.splitlines() if l.startswith("SHAPE ")).split()[1:])
    assert (h, w) == (240, 360) and n == n2 and (h2, w2, c) == (h, w, 3) and (h3, w3) == (h, w)
    manifest = json.loads((tmp_path / "out" / "chart" / "render.json").read_text())
    assert (manifest["height"], manifest["width"], manifest["bands"]["count"]) == (h, w, n)
