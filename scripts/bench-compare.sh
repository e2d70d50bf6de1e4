#!/usr/bin/env bash
# Side-by-side benchmark: builds OLD_COMMIT (a git worktree under /tmp) and the working tree in Release, then
# times them ALTERNATELY in one run (old, new, old, new, ...) so that a slow phase of the machine, or another
# build running beside us, hits both builds alike. Prints per-case medians and the ratio new/old. The working tree
# is measured twice: as `dotnet spectral.dll` (new, the build `dotnet run` uses) and as its native command (native,
# `dotnet publish -p:SpectralNative=true`, README "Install"; BENCH_NATIVE=0 leaves it out), both against OLD's dll.
#
#   usage: scripts/bench-compare.sh OLD_COMMIT [ROUNDS]        (ROUNDS ≥ 5, default 7)
#
# Cases (meshes from SPECTRAL_MODELS, default /work/shared/models):
#   bunny1024      `spectral bench`, bunny 1024², 1 spp: the render median (in-process, after a warm-up)
#   bunny512x16    bunny 512², 16 spp: render median
#   igea1024       statue (Igea, 268,686 triangles) 1024², 1 spp: render median
#   bunny512b401   bunny 512², 401 bands (380:780:401): render median
#   process512     one whole `spectral render` of the bunny at 512², all outputs, wall time (/usr/bin/time)
#   peak1024       peak working set of `spectral bench` at bunny 1024² (MB; lower is better)
#   pathbunny      the path tracer: the §3.4 bunny under a daylight sky (scenes/path-bunny-daylight-sky.json), 320×240,
#                  16 spp: render median
#   pathroom       the path tracer: the Cornell-like room with an area light (scenes/path-cornell-room.json), 320×240,
#                  16 spp: render median
# Every round runs each case once for each build; a bench case's figure is the render_s its `bench:` line
# prints (the median of --repeat renders in that process), the figure of the case is the median over rounds.
# Only ratios from one such run are fair figures: absolute times move with the machine's phase.
set -euo pipefail

old=${1:?usage: scripts/bench-compare.sh OLD_COMMIT [ROUNDS]}
rounds=${2:-7}
(( rounds >= 5 )) || { echo "bench-compare: ROUNDS must be at least 5 (got $rounds)" >&2; exit 2; }
repo=$(git rev-parse --show-toplevel)
cd "$repo"
oldsha=$(git rev-parse --verify "$old^{commit}") || { echo "bench-compare: '$old' is not a commit" >&2; exit 2; }
export SPECTRAL_MODELS=${SPECTRAL_MODELS:-/work/shared/models}
[[ -f $SPECTRAL_MODELS/stanford-bunny.obj ]] || { echo "bench-compare: no stanford-bunny.obj in SPECTRAL_MODELS=$SPECTRAL_MODELS" >&2; exit 2; }

oldtree=/tmp/bench-compare-${oldsha:0:12}
if [[ ! -d $oldtree ]]; then
    git worktree add --detach "$oldtree" "$oldsha" >/dev/null
fi
echo "building old ${oldsha:0:12} in $oldtree and new (working tree $repo), Release ..." >&2
dotnet build -c Release -v q -nologo "$oldtree/src/SpectralRenderer.Cli" >/dev/null
dotnet build -c Release -v q -nologo "$repo/src/SpectralRenderer.Cli" >/dev/null
OLD=$oldtree/src/SpectralRenderer.Cli/bin/Release/net10.0/spectral.dll
NEW=$repo/src/SpectralRenderer.Cli/bin/Release/net10.0/spectral.dll
out=$(mktemp -d /tmp/bench-compare-out.XXXXXX)
trap 'rm -rf "$out"' EXIT
# The working tree's native command too (README, "Install": Native AOT, the form installed for speed), as a third
# build "native", unless BENCH_NATIVE=0. Its own artifacts path: the build above is not touched.
builds=(old new)
if [[ ${BENCH_NATIVE:-1} != 0 ]]; then
    echo "publishing the working tree's native command (-p:SpectralNative=true) ..." >&2
    dotnet publish -c Release -v q -nologo "$repo/src/SpectralRenderer.Cli" -p:SpectralNative=true \
        --artifacts-path "$out/native-artifacts" -o "$out/native" >/dev/null
    NATIVE=$out/native/spectral
    builds+=(native)
fi
# Both builds read the same scene files (the old commit's, so a scene change in the working tree is not measured).
S=$oldtree/scenes

field() { sed -n "s/.*\b$1=\([0-9.]*\).*/\1/p"; }
run_case() { # build case → one figure
    local b=$1 c=$2 run
    case $b in old) run=(dotnet "$OLD") ;; new) run=(dotnet "$NEW") ;; native) run=("$NATIVE") ;; esac
    case $c in
        bunny1024)    "${run[@]}" bench "$S/paper-3.2-bunny-14.json" --width 1024 --height 1024 --repeat 5 | grep '^bench:' | field render_s ;;
        bunny512x16)  "${run[@]}" bench "$S/paper-3.2-bunny-14.json" --width 512 --height 512 --spp 16 --repeat 3 | grep '^bench:' | field render_s ;;
        igea1024)     "${run[@]}" bench "$S/paper-3.3-statue-D65.json" --width 1024 --height 1024 --repeat 5 | grep '^bench:' | field render_s ;;
        bunny512b401) "${run[@]}" bench "$S/paper-3.2-bunny-14.json" --width 512 --height 512 --bands 380:780:401 --repeat 5 | grep '^bench:' | field render_s ;;
        process512)   rm -rf "$out/r"; /usr/bin/time -f %e -o "$out/time" "${run[@]}" render "$S/paper-3.2-bunny-14.json" -o "$out/r" --width 512 --height 512 --quiet >/dev/null; cat "$out/time" ;;
        peak1024)     "${run[@]}" bench "$S/paper-3.2-bunny-14.json" --width 1024 --height 1024 --repeat 1 | grep '^bench:' | field peak_ws_mb ;;
        pathbunny)    "${run[@]}" bench "$S/path-bunny-daylight-sky.json" --width 320 --height 240 --spp 16 --repeat 3 | grep '^bench:' | field render_s ;;
        pathroom)     "${run[@]}" bench "$S/path-cornell-room.json" --width 320 --height 240 --spp 16 --repeat 3 | grep '^bench:' | field render_s ;;
    esac
}

# BENCH_CASES="peak1024 process512" runs only those cases.
read -r -a cases <<< "${BENCH_CASES:-bunny1024 bunny512x16 igea1024 bunny512b401 process512 peak1024 pathbunny pathroom}"
declare -A figures
for ((r = 1; r <= rounds; r++)); do
    echo "round $r/$rounds" >&2
    for c in "${cases[@]}"; do
        # Alternate which build goes first from round to round.
        if (( r % 2 )); then order=("${builds[@]}"); else order=(); for ((i = ${#builds[@]} - 1; i >= 0; i--)); do order+=("${builds[i]}"); done; fi
        for b in "${order[@]}"; do
            v=$(run_case "$b" "$c")
            [[ -n $v ]] || { echo "bench-compare: case $c of the $b build printed no figure" >&2; exit 1; }
            figures[$c.$b]+="$v "
        done
    done
done

median() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; date: $(date -u '+%Y-%m-%d %H:%M UTC'); old ${oldsha:0:12}, new $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- src || echo '+changes'); $rounds alternating rounds"
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.3f", a / b}'; }
printf '%-14s %-5s %9s %9s %9s %9s %11s   %s\n' case unit old new native new/old native/old "all rounds (old | new | native)"
for c in "${cases[@]}"; do
    unit=s; [[ $c == peak1024 ]] && unit=MB
    mo=$(echo "${figures[$c.old]}" | median); mn=$(echo "${figures[$c.new]}" | median)
    ma=-; ra=-; [[ -n ${figures[$c.native]:-} ]] && { ma=$(echo "${figures[$c.native]}" | median); ra=$(ratio "$ma" "$mo"); }
    printf '%-14s %-5s %9s %9s %9s %9s %11s   %s| %s| %s\n' "$c" "$unit" "$mo" "$mn" "$ma" "$(ratio "$mn" "$mo")" "$ra" "${figures[$c.old]}" "${figures[$c.new]}" "${figures[$c.native]:-}"
done
