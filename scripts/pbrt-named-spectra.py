#!/usr/bin/env python3
"""Extract pbrt-v4's named spectra (illuminants, metals, glasses) from its source into data/pbrt-v4/*.csv.

    python3 scripts/pbrt-named-spectra.py SPECTRUM_CPP [OUT_DIR]

SPECTRUM_CPP is pbrt-v4's src/pbrt/util/spectrum.cpp (github.com/mmp/pbrt-v4, Apache-2.0; the tables were
extracted from commit 5f7a606806a4ac7b939131ded9d7a30ebd02416e, e.g. `git show 5f7a606:src/pbrt/util/spectrum.cpp`).
The script reads the `namedSpectra` map (each name → the `FromInterleaved(ARRAY, normalize, …)` it is built from)
and each `const Float ARRAY[] = { λ, v, λ, v, … };`, and writes one CSV per shared wavelength grid, the numbers
copied as the source spells them (no rounding). Camera sensitivities in the same map are left out. Columns are
pbrt's names; files named illuminants-*.csv hold the spectra pbrt normalises (normalize = true: scaled so that
Σ ȳ(λ)·S(λ) over 360..830 nm equals CIE_Y_integral), which the importer applies, the others are used as they are.
"""
import re
import sys
from pathlib import Path

source = Path(sys.argv[1]).read_text()
out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(__file__).resolve().parents[1] / "data" / "pbrt-v4"

arrays = {}
for m in re.finditer(r"const Float (\w+)\[\w*\] = \{(.*?)\};", source, re.S):
    cells = [c.strip() for c in m.group(2).replace("\n", " ").split(",") if c.strip()]
    arrays[m.group(1)] = (cells, source[: m.start()].count("\n") + 1)

# Spectrum var = PiecewiseLinearSpectrum::FromInterleaved(ARRAY, true|false, alloc);
made = {v: (a, n == "true") for v, a, n in re.findall(
    r"Spectrum (\w+) =\s*PiecewiseLinearSpectrum::FromInterleaved\((\w+), (true|false), alloc\);", source)}
table = re.search(r"namedSpectra = \{(.*?)\n    \};", source, re.S).group(1)
named = [(name, var) for name, var in re.findall(r'\{"([\w-]+)", (\w+)\}', table) if var in made]

groups = {}   # file stem -> (wavelength strings, [(name, values, array, line)])
for name, var in named:
    array, normalise = made[var]
    cells, line = arrays[array]
    assert len(cells) % 2 == 0, array
    lam, val = cells[0::2], cells[1::2]
    family = name.split("-")[0]
    if normalise:
        stem = "illuminants-300-830" if float(lam[0]) == 300 else "illuminants-fluorescent"
    elif family == "metal":
        element = name.split("-")[1]
        stem = "metals-Ag-Al-Au-Cu" if element in ("Ag", "Al", "Au", "Cu") else f"metal-{element}"
    else:
        stem = name
    assert normalise == stem.startswith("illuminants"), name
    grid, columns = groups.setdefault(stem, (lam, []))
    assert [float(x) for x in grid] == [float(x) for x in lam], f"{name}: not the grid of {stem}"
    columns.append((name, val, array, line))

out.mkdir(parents=True, exist_ok=True)
for stem, (lam, columns) in sorted(groups.items()):
    rows = ["wavelength_nm," + ",".join(c[0] for c in columns)]
    for i, l in enumerate(lam):
        rows.append(",".join([l] + [c[1][i] for c in columns]))
    (out / f"{stem}.csv").write_text("\n".join(rows) + "\n")
    for name, _, array, line in columns:
        print(f"{stem}.csv\t{name}\t{array}\tspectrum.cpp:{line}\t{len(lam)} samples")
