#!/usr/bin/env bash
# Noise at equal time of two variants of one scene (issue 40: the light tree, window portals): renders A and B
# alternately ROUNDS times (A, B, A, B, ...: a slow phase of a shared machine hits both alike) with the working tree's
# build, each with the noise product, and prints per variant the median render time (render.json timings_s.render), the
# mean relative standard error of luminance (sampling.noise; the same every round: renders are deterministic) and the
# error at B's median time, err·sqrt(t/t_B) (the error falls as 1/sqrt(samples)).
#
#   usage: scripts/noise-at-equal-time.sh A.json B.json [ROUNDS (default 5)] [render options, e.g. --spp 64]
set -euo pipefail
a=${1:?usage: noise-at-equal-time.sh A.json B.json [ROUNDS] [options]}; b=${2:?B.json}; rounds=${3:-5}; shift 3 || shift $#
repo=$(cd "$(dirname "$0")/.." && pwd)
dll=$repo/src/SpectralRenderer.Cli/bin/Release/net10.0/spectral.dll
[[ -f $dll ]] || dotnet build -c Release -v q -nologo "$repo/src/SpectralRenderer.Cli" >/dev/null
out=$(mktemp -d /tmp/noise-equal-time.XXXXXX); trap 'rm -rf "$out"' EXIT
for ((r = 0; r < rounds; r++)); do
    for v in a b; do
        scene=$a; [[ $v == b ]] && scene=$b
        dotnet "$dll" render "$scene" -o "$out/$v" --formats png,noise --threads 2 --quiet "$@" >/dev/null
        python3 -c "import json,sys; d=json.load(open('$out/$v/render.json')); print(d['timings_s']['render'], d['sampling']['noise']['relative_error_of_luminance']['mean'])" >> "$out/$v.txt"
    done
done
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; date: $(date -u '+%Y-%m-%d %H:%M UTC'); $rounds alternating rounds; options: $*"
python3 - "$out" "$a" "$b" <<'PY'
import statistics, sys, math
out, names = sys.argv[1], {"a": sys.argv[2], "b": sys.argv[3]}
rows = {}
for v in "ab":
    runs = [tuple(map(float, l.split())) for l in open(f"{out}/{v}.txt")]
    rows[v] = (statistics.median(t for t, _ in runs), runs[0][1])
tb = rows["b"][0]
for v in "ab":
    t, e = rows[v]
    print(f"{v} {names[v]}: render {t:.2f} s (median), mean relative SE of luminance {e:.4f}, at B's time {e * math.sqrt(t / tb):.4f}")
ea = rows["a"][1] * math.sqrt(rows["a"][0] / tb)
print(f"A/B error at equal time: {ea / rows['b'][1]:.3f}")
PY
