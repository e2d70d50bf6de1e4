#!/usr/bin/env bash
# Relight versus the render it replaces, whole process, in one run (issue 15's bar: relight ≥ 10× faster).
#
#   usage: scripts/bench-relight.sh [ROUNDS] [SIZE] [SPP...]        (defaults: 5 rounds, 1024, the scene's own spp and 1)
#
# The §3.2 bunny (scenes/paper-3.2-bunny-14.json; meshes from SPECTRAL_MODELS, default /work/shared/models) is rendered
# once under CIE A with every output and the per-light outputs (--formats all,lights). Then, per round and per spp,
# ALTERNATELY (so a slow phase of a shared machine hits both alike):
#   render   `spectral render` of the scene under D65 itself, same size, spp and outputs: the render relight replaces
#   relight  `spectral relight A --light D65=D65`: the same folder, no ray traced
# each timed as one whole process (/usr/bin/time: start-up, scene load, trace or read, every file written), into an
# output folder removed beforehand (so neither pays for deleting a previous render). The relit folder is checked to
# list the same files as the direct render. Printed per spp: the median wall time of each and their ratio, and from the
# relit render.json the seconds the writers took (run.write_s) and the relight's own compute (run.relit.compute_s):
# the render can be at most (render time) / (relight's start-up + writes) times slower than a relight that writes
# every file a render writes.
set -euo pipefail

rounds=${1:-5}
size=${2:-1024}
shift $(( $# >= 2 ? 2 : $# )) || true
repo=$(git rev-parse --show-toplevel)
cd "$repo"
export SPECTRAL_MODELS=${SPECTRAL_MODELS:-/work/shared/models}
[[ -f $SPECTRAL_MODELS/stanford-bunny.obj ]] || { echo "bench-relight: no stanford-bunny.obj in SPECTRAL_MODELS=$SPECTRAL_MODELS" >&2; exit 2; }
scene=scenes/paper-3.2-bunny-14.json
own_spp=$(sed -n 's/.*"spp": *\([0-9]*\).*/\1/p' "$scene" | head -1)
spps=("$@")
(( ${#spps[@]} > 0 )) || spps=("$own_spp" 1)

if [[ ${BENCH_NO_BUILD:-0} != 1 && -z ${BENCH_DLL:-} ]]; then
    echo "building $repo (Release, ReadyToRun) ..." >&2
    dotnet build -c Release -v q -nologo src/SpectralRenderer.Cli >/dev/null
fi
# BENCH_DLL: another build's spectral.dll to measure instead (e.g. an older commit's, for a before/after).
B=${BENCH_DLL:-$repo/src/SpectralRenderer.Cli/bin/Release/net10.0/spectral.dll}
out=$(mktemp -d /tmp/bench-relight.XXXXXX)
trap 'rm -rf "$out"' EXIT
spectral=(dotnet "$B")
# BENCH_NATIVE=1: the working tree's native command instead (README, "Install"), published into the scratch folder.
if [[ ${BENCH_NATIVE:-0} == 1 ]]; then
    echo "publishing the native command (-p:SpectralNative=true) ..." >&2
    dotnet publish -c Release -v q -nologo "$repo/src/SpectralRenderer.Cli" -p:SpectralNative=true --artifacts-path "$out/artifacts" -o "$out/native" >/dev/null
    B=$out/native/spectral
    spectral=("$B")
fi
sed 's/"spectrum": "D65"/"spectrum": "A"/' "$scene" > "$out/bunny-A.json"
grep -q '"spectrum": "A"' "$out/bunny-A.json" || { echo "bench-relight: could not make the scene's light CIE A" >&2; exit 1; }

timed() { # output file, command… → wall seconds
    local t=$1; shift
    /usr/bin/time -f %e -o "$t" "$@" >/dev/null 2>"$t.err" || { cat "$t.err" >&2; exit 1; }
    cat "$t"
}
median() { printf '%s\n' "$@" | sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
json() { python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); print(eval(sys.argv[2], {}, {"d": d}))' "$@"; }

echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; $(date -u '+%Y-%m-%d %H:%M UTC'); commit $(git rev-parse --short HEAD)$(git diff --quiet HEAD || echo '+changes'); $B"
printf '%-6s %-5s %10s %10s %8s %10s %10s   %s\n' spp size render_s relight_s ratio write_s compute_s "all rounds (render | relight)"
for spp in "${spps[@]}"; do
    "${spectral[@]}" render "$out/bunny-A.json" -o "$out/A" --width "$size" --height "$size" --spp "$spp" --formats all,lights --quiet
    render=() relight=()
    for ((r = 1; r <= rounds; r++)); do
        # The order alternates from round to round too.
        for which in $( (( r % 2 )) && echo "render relight" || echo "relight render"); do
            rm -rf "$out/$which"
            if [[ $which == render ]]; then
                render+=("$(timed "$out/t" "${spectral[@]}" render "$scene" -o "$out/render" --width "$size" --height "$size" --spp "$spp" --formats all,lights --quiet)")
            else
                relight+=("$(timed "$out/t" "${spectral[@]}" relight "$out/A" --light D65=D65 -o "$out/relight" --quiet)")
            fi
        done
    done
    same=$(json "$out/render/render.json" 'sorted(d["files"])' ; json "$out/relight/render.json" 'sorted(d["files"])')
    [[ "$(sed -n 1p <<< "$same")" == "$(sed -n 2p <<< "$same")" ]] || { echo "bench-relight: the relit folder lists other files than the render:" >&2; echo "$same" >&2; exit 1; }
    w=$(json "$out/relight/render.json" 'd["run"].get("write_s", "nan")')
    c=$(json "$out/relight/render.json" 'd["run"]["relit"].get("compute_s", "nan")')
    mr=$(median "${render[@]}"); ml=$(median "${relight[@]}")
    printf '%-6s %-5s %10s %10s %8.2f %10.3f %10.3f   %s | %s\n' "$spp" "$size" "$mr" "$ml" "$(echo "$mr / $ml" | bc -l)" "$w" "$c" "${render[*]}" "${relight[*]}"
done
