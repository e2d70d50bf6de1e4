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
