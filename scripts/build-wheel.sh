#!/usr/bin/env bash
# Builds the Python wheel (README, "Python"): publishes libspectral.so Native AOT (src/SpectralRenderer.Native), copies
# it and the data/ tables into python/spectralrenderer/, and builds dist/spectralrenderer-*.whl for this machine.
#
#   usage: scripts/build-wheel.sh [DIST_DIR]          (default dist/)
#
# Needs what the native CLI needs (README, "Install": the ILCompiler packs from NuGet, clang and zlib1g-dev) and Python 3
# with pip, setuptools and wheel (Debian: python3-pip python3-setuptools python3-wheel); nothing is downloaded by pip.
# SPECTRAL_NATIVE_DIR=DIR reuses a publish made before (a folder holding libspectral.so).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd); cd "$repo"
dist=$(mkdir -p "${1:-dist}" && cd "${1:-dist}" && pwd)
# The first Python with setuptools and wheel (a pyenv python3 on PATH may lack them; Debian's /usr/bin/python3 has them).
python=${PYTHON:-}
if [[ -z $python ]]; then
    for p in python3 /usr/bin/python3; do
        if command -v "$p" >/dev/null && "$p" -c 'import setuptools, wheel, pip' 2>/dev/null; then python=$p; break; fi
    done
    [[ -n $python ]] || { echo "build-wheel: no python3 with pip, setuptools and wheel (Debian: python3-pip python3-setuptools python3-wheel)" >&2; exit 2; }
fi
native=${SPECTRAL_NATIVE_DIR:-}
if [[ -z $native ]]; then
    native=$(mktemp -d /tmp/libspectral.XXXXXX); trap 'rm -rf "$native" "$native.artifacts"' EXIT
    dotnet publish src/SpectralRenderer.Native/SpectralRenderer.Native.csproj -c Release -p:SpectralNative=true \
        --artifacts-path "$native.artifacts" -o "$native" -v q -nologo
fi
pkg=python/spectralrenderer
cp "$native/libspectral.so" "$pkg/libspectral.so"
mkdir -p "$pkg/data" && cp data/*.csv "$pkg/data/"
rm -rf python/build python/*.egg-info
"$python" -m pip wheel --no-deps --no-build-isolation --no-index -w "$dist" python/ >/dev/null
rm -rf python/build python/*.egg-info
ls "$dist"/spectralrenderer-*.whl
