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
    probe = ("\nprint('SHAPE', *r.cube.shape, len(r.wavelengths), *r.xyz.shape, *r.ids.shape)"
             "\nprint('LED', float(led.xyz[..., 1].mean() / r.xyz[..., 1].mean()))\n")
    env = {**os.environ, "PYTHONPATH": str(repo / "python")}
    done = subprocess.run([sys.executable, "-c", snippet + probe], cwd=tmp_path, capture_output=True, text=True, env=env)
    assert done.returncode == 0, done.stderr
    h, w, n, n2, h2, w2, c, h3, w3 = map(int, next(l for l in done.stdout.splitlines() if l.startswith("SHAPE ")).split()[1:])
    assert (h, w) == (240, 360) and n == n2 and (h2, w2, c) == (h, w, 3) and (h3, w3) == (h, w)
    # Issue 42: the LED relight is lit. Its shape on the built-in lights' scale carries D65's luminous flux, at intensity 0.5,
    # with A (∫V·A 2 % above ∫V·D65) as the white: a neutral surface keeps 0.5/1.02 of its luminance; the chart's colours
    # under blue light move the mean only within a factor 1.5 of that (the shape as given would be ~0.003: black).
    led = float(next(l for l in done.stdout.splitlines() if l.startswith("LED ")).split()[1])
    assert 0.49 / 1.5 <= led <= 0.49 * 1.5, led
    assert "RuntimeWarning" not in done.stderr, done.stderr
    manifest = json.loads((tmp_path / "out" / "chart" / "render.json").read_text())
    assert (manifest["height"], manifest["width"], manifest["bands"]["count"]) == (h, w, n)
