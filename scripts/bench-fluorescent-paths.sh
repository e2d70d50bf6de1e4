#!/usr/bin/env bash
# Fluorescent paths, before and after (issue 26, BENCHMARKS.md "Fluorescent paths: lobe choice"): a small booth under the
# path integrator — "room": every wall the brightened paper (scenes/oba-paper-matrix.csv); "sheet": white walls (0.9) and a
# sheet of the paper on the back wall — lit by a D65 area lamp, bands 300:780:48 (the UV that excites the brightener).
# Renders it with OLD_DLL and NEW_DLL at SPP samples per pixel for seeds 1..SEEDS (one thread each), and a reference with
# NEW_DLL at REF_SPP (seed 101); prints per build, for luminance Y and the 440–450 nm band over the back wall's centre
# (the middle half of the picture): the region mean ± its standard error over seeds (and the reference's), the per-pixel
# relative standard deviation across seeds, the RMS error against the reference (relative to the region mean), the largest
# pixel over the region mean (fireflies), and the render time per camera sample.
#
#   usage: scripts/bench-fluorescent-paths.sh OLD_DLL NEW_DLL [room|sheet] [SPP=16] [SEEDS=8] [REF_SPP=4096]
set -euo pipefail
old=${1:?usage: scripts/bench-fluorescent-paths.sh OLD_DLL NEW_DLL [room|sheet] [SPP] [SEEDS] [REF_SPP]}; new=${2:?}
kind=${3:-room}; spp=${4:-16}; seeds=${5:-8}; refspp=${6:-4096}
repo=$(git rev-parse --show-toplevel)
out=$(mktemp -d /tmp/bench-fluorescent.XXXXXX); trap 'rm -rf "$out"' EXIT
scene() {   # scene SEED SPP > json
    local walls=paper sheet=''
    if [[ $kind == sheet ]]; then
        walls=booth
        sheet=', { "type": "quad", "name": "sheet", "center": [0, 0, -1.99], "size": [5, 4], "normal": [0, 0, 1], "material": "paper" }'
    fi
    cat <<JSON
{ "name": "fluorescent-$kind", "bands": "300:780:48", "radiometry": "physical", "white": "D65",
  "integrator": { "type": "path", "seed": $1 },
  "camera": { "position": [0, 0, 6], "look_at": [0, 0, 0], "fov": 50, "width": 48, "height": 32, "spp": $2 },
  "materials": {
    "paper": { "type": "lambertian", "fluorescence": { "matrix": "$repo/scenes/oba-paper-matrix.csv" } },
    "booth": { "type": "lambertian", "reflectance": 0.9 },
    "lamp": { "type": "lambertian", "reflectance": 0, "emission": { "spectrum": "D65", "radiance": 0.1 } } },
  "objects": [
    { "type": "box", "name": "room", "min": [-4, -3, -2], "max": [4, 3, 7], "material": "$walls" },
    { "type": "quad", "name": "lamp", "center": [0, 2.99, 1.5], "size": [4, 1], "normal": [0, -1, 0], "up": [0, 0, -1], "material": "lamp" }$sheet ],
  "output": { "formats": ["npy"] } }
JSON
}
render() {  # render DLL TAG SEED SPP
    scene "$3" "$4" > "$out/$2-$3.json"
    dotnet "$1" render "$out/$2-$3.json" -o "$out/$2-$3" --threads 1 --quiet
}
render "$new" ref 101 "$refspp"
for s in $(seq 1 "$seeds"); do render "$old" old "$s" "$spp"; render "$new" new "$s" "$spp"; done
python3 - "$out" "$seeds" "$spp" <<'PY'
import sys, ast, array, math, json
out, seeds, spp = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def load(path, c):
    b = open(path, 'rb').read()
    hl = int.from_bytes(b[8:10], 'little'); hdr = ast.literal_eval(b[10:10 + hl].decode())
    a = array.array('f'); a.frombytes(b[10 + hl:]); C = hdr['shape'][-1]
    return [a[i] for i in range(c, len(a), C)], hdr['shape']
def chans(run):
    y, sh = load(f'{out}/{run}/xyz.npy', 1)
    return {'Y': y, '440-450nm': load(f'{out}/{run}/spectral.npy', 14)[0]}, sh
ref, sh = chans('ref-101')
H, W = sh[0], sh[1]
reg = [y * W + x for y in range(H // 4, 3 * H // 4) for x in range(W // 4, 3 * W // 4)]
for tag in ('old', 'new'):
    runs = [chans(f'{tag}-{s}')[0] for s in range(1, seeds + 1)]
    times = [json.load(open(f'{out}/{tag}-{s}/render.json'))['timings_s']['render'] for s in range(1, seeds + 1)]
    for ch in ('Y', '440-450nm'):
        r = ref[ch]; rm = sum(r[i] for i in reg) / len(reg)
        means = [sum(run[ch][i] for i in reg) / len(reg) for run in runs]
        m = sum(means) / seeds; sm = math.sqrt(sum((x - m) ** 2 for x in means) / (seeds - 1) / seeds)
        rel = []
        for i in reg:
            v = [run[ch][i] for run in runs]; mu = sum(v) / seeds
            rel.append(math.sqrt(sum((x - mu) ** 2 for x in v) / (seeds - 1)) / r[i])
        rms = math.sqrt(sum((run[ch][i] - r[i]) ** 2 for run in runs for i in reg) / (seeds * len(reg))) / rm
        peak = max(run[ch][i] for run in runs for i in range(H * W)) / rm
        print(f'{tag} {ch:9}: region mean {m:.5g} ± {sm:.2g} (reference {rm:.5g}); per-pixel rel. sd over {seeds} seeds '
              f'{sum(rel) / len(rel):.3f} (median {sorted(rel)[len(rel) // 2]:.3f}); RMS error {rms:.3f}; largest pixel / mean {peak:.1f}')
    t = sum(times) / seeds
    print(f'{tag}: {spp} spp, {W}x{H}, render {t:.3f} s (1 thread) = {1e6 * t / (H * W * spp):.2f} µs per camera sample')
PY
