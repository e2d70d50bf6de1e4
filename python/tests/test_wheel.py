"""README, "Python": the wheel installs into a fresh venv holding only NumPy and renders with no .NET on PATH (the library
is Native AOT): the chart's cube equals the CLI's spectral.npy bit for bit, and nothing is written outside the caller's
own files (no temporary files)."""
import os
import subprocess
import sys
import venv
from pathlib import Path

import numpy as np
import pytest


def test_the_wheel_installs_into_a_fresh_venv_with_only_numpy_and_renders_without_dotnet(sr, repo, tmp_path, cli_chart_npy):
    from spectralrenderer import _native
    lib = _native._locate()
    dist = tmp_path / "dist"
    build = subprocess.run(["bash", str(repo / "scripts/build-wheel.sh"), str(dist)], capture_output=True, text=True,
                           env={**os.environ, "SPECTRAL_NATIVE_DIR": str(lib.parent), "PYTHON": sys.executable})
    if build.returncode != 0 and "No module named pip" in build.stderr:
        pytest.skip("pip is not installed for this Python (Debian: python3-pip)")
    assert build.returncode == 0, build.stderr
    wheel = next(dist.glob("spectralrenderer-*.whl"))
    assert "none-linux" in wheel.name or "none-" in wheel.name   # tagged for this platform, not py3-none-any
    assert "-any.whl" not in wheel.name
    env_dir = tmp_path / "venv"
    # A venv that sees no system packages, with the one dependency, NumPy, put in it (this Python's NumPy and its
    # metadata, linked: no index to reach), so pip resolves the wheel's dependency from it alone.
    venv.create(env_dir, with_pip=True, system_site_packages=False)
    py = env_dir / "bin" / "python"
    site = Path(subprocess.run([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                               capture_output=True, text=True, check=True).stdout.strip())
    numpy_dir = Path(np.__file__).parent
    linked = [p for p in numpy_dir.parent.iterdir() if p.name == "numpy" or p.name.startswith(("numpy-", "numpy.libs"))]
    for p in linked:
        (site / p.name).symlink_to(p)
    metadata = any(p.name.endswith((".dist-info", ".egg-info")) for p in linked)
    p = subprocess.run([str(py), "-m", "pip", "install", "--no-index", *([] if metadata else ["--no-deps"]), str(wheel)],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    # Only the venv on PATH (no dotnet), no SPECTRAL_* variables, a working folder without data/, TMPDIR empty.
    work, tmp = tmp_path / "work", tmp_path / "tmp"
    work.mkdir(), tmp.mkdir()
    env = {"PATH": str(env_dir / "bin"), "HOME": str(work), "TMPDIR": str(tmp)}
    cube = tmp_path / "cube.npy"
    code = ("import spectralrenderer as sr, numpy as np, shutil, sys, importlib.util as u;"
            "assert shutil.which('dotnet') is None;"
            "assert not [m for m in ('matplotlib', 'colour', 'pytest') if u.find_spec(m)], 'the venv holds more than NumPy';"
            f"r = sr.render({str(repo / 'scenes/paper-3.1-colorchecker-d65.json')!r});"
            f"open({str(cube)!r}, 'wb').write(r.cube.tobytes());"
            "print(r.cube.shape, sr.__file__)")
    p = subprocess.run([str(py), "-c", code], capture_output=True, text=True, env=env, cwd=work)
    assert p.returncode == 0, p.stderr
    assert "(480, 720, 20)" in p.stdout and str(env_dir) in p.stdout
    assert cube.read_bytes() == np.load(cli_chart_npy / "spectral.npy").tobytes()
    assert list(work.iterdir()) == [] and list(tmp.iterdir()) == []   # no files in between
