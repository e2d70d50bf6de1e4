#!/usr/bin/env bash
# Regenerates docs/validation/ (report.html, results.json, results.csv): `spectral validate`, the full set, with the
# Release build of the CLI (build it first: dotnet build SpectralRenderer.sln -c Release). ValidationTests checks that
# the committed results.json lists exactly the registry's cases with the same references and tolerances, each within
# tolerance; rerun this after changing a case. Extra arguments go to `spectral validate` (e.g. --threads 2).
set -euo pipefail
cd "$(dirname "$0")/.."
cli=src/SpectralRenderer.Cli/bin/Release/net10.0/spectral.dll
[ -f "$cli" ] || { echo "validation-report.sh: $cli is missing (hint: dotnet build SpectralRenderer.sln -c Release)" >&2; exit 2; }
dotnet "$cli" validate -o docs/validation "$@"
