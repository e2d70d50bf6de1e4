#!/usr/bin/env bash
# The calls left in the machine code of hot methods: runs one small `spectral bench` with the JIT's disassembly of the
# named methods (DOTNET_JitDisasm, release runtime) and lists, per method, its inlinee counts, its frame size and every
# call instruction that remains, most frequent first. A helper marked AggressiveInlining that shows up here was not
# inlined: the JIT stops inlining into a method once its inlining budget is spent (BENCHMARKS.md, "The path walk's
# inlining"), and the band arithmetic and vector maths of a hot loop must not become calls.
#
#   usage: scripts/jit-calls.sh [DLL] [METHODS] [SCENE]
#     DLL      the build's spectral.dll (default: this tree's Release build)
#     METHODS  DOTNET_JitDisasm's list, *Class:Method (default "*PathIntegrator:Walk *PathIntegrator:NextEvent": the path
#              tracer's walk and its next-event estimation)
#     SCENE    the scene benched, 80x60, 4 spp (default scenes/path-cornell-room.json)
#
# For a profile with the JIT's frames named, run `perf record` with DOTNET_PerfMapEnabled=1 and
# DOTNET_EnableWriteXorExecute=0 (without the latter the code runs from a double mapping that perf cannot name).
set -euo pipefail
repo=$(git rev-parse --show-toplevel)
dll=${1:-$repo/src/SpectralRenderer.Cli/bin/Release/net10.0/spectral.dll}
methods=${2:-*PathIntegrator:Walk *PathIntegrator:NextEvent}
scene=${3:-$repo/scenes/path-cornell-room.json}
[[ -f $dll ]] || { echo "jit-calls: no build at $dll (dotnet build -c Release first)" >&2; exit 2; }
export SPECTRAL_MODELS=${SPECTRAL_MODELS:-$repo/../shared/models}
out=$(mktemp /tmp/jit-calls.XXXXXX)
trap 'rm -f "$out"' EXIT
DOTNET_JitDisasm="$methods" DOTNET_JitStdOutFile=$out \
    dotnet "$dll" bench "$scene" --width 80 --height 60 --spp 4 --repeat 1 --threads 1 >/dev/null
awk '/; Assembly listing for method/ { m = $0; sub(/.*for method /, "", m); sub(/\(.*/, "", m); print "== " m }
     /inlinees|Lcl frame size|sub +rsp,/ { print "   " $0 }' "$out"
awk '/; Assembly listing for method/ { m = $0; sub(/.*for method /, "", m); sub(/\[.*/, "", m) }
     / call / { c = $0; sub(/.* call +/, "", c); print m " -> " c }' "$out" | sort | uniq -c | sort -rn
