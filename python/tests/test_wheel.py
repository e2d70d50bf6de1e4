"""README, "Python": the wheel installs into a fresh venv and renders with no .NET on PATH (the library is Native AOT)."""
import os
import subprocess
import sys
import venv

import pytest


def test_the_wheel_installs_into_a_fresh_venv_and_renders_without_dotnet(sr, repo, tmp_path):
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
    # NumPy from the system (Debian's python3-numpy): the venv has no other package and no index to reach.
    venv.create(env_dir, with_pip=True, system_site_packages=True)
    py = env_dir / "bin" / "python"
    p = subprocess.run([str(py), "-m", "pip", "install", "--no-index", "--no-deps", str(wheel)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    # Only the venv on PATH (no dotnet), no SPECTRAL_* variables, a working folder without data/.
    env = {"PATH": str(env_dir / "bin"), "HOME": str(tmp_path)}
    code = ("import spectralrenderer as sr, shutil; assert shutil.which('dotnet') is None;"
            f"r = sr.render({str(repo / 'scenes/paper-3.1-colorchecker-d65.json')!r}, width=24, height=16);"
            "print(r.cube.shape, sr.__file__)")
    p = subprocess.run([str(py), "-c", code], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert "(16, 24, 20)" in p.stdout and str(env_dir) in p.stdout
