#!/usr/bin/env bash
# Coverage-guided fuzzing of the readers: SharpFuzz instruments the engine assembly, AFL++ drives each target
# (fuzz/SpectralRenderer.Fuzz/Program.cs) from its committed seeds (fuzz/seeds/TARGET) for a bounded time.
# Exits 1 when any target saved a crash or a hang, listing the inputs (reproduce with the uninstrumented build:
#   dotnet fuzz/SpectralRenderer.Fuzz/bin/Release/net10.0/SpectralRenderer.Fuzz.dll TARGET FILE).
# usage: fuzz/run.sh [SECONDS_PER_TARGET] [TARGET...]      needs afl-fuzz (Debian: afl++) and network for NuGet
set -uo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"; shift || true
targets=("$@"); [ ${#targets[@]} -gt 0 ] || targets=(scene csv obj ply exr matrix envi npy densitygrid png jpeg hdr ies ldt manifest lights camera sweep sensor mitsuba pbrt gltf)
export DOTNET_CLI_TELEMETRY_OPTOUT=1 DOTNET_NOLOGO=1
command -v afl-fuzz >/dev/null || { echo "fuzz: afl-fuzz not found (apt-get install afl++)"; exit 1; }

work="${FUZZ_WORK:-$(mktemp -d /tmp/spectral-fuzz.XXXXXX)}"; mkdir -p "$work"
tool="$work/tool"
dotnet build fuzz/SpectralRenderer.Fuzz -c Release -v q -nologo >"$work/build.log" 2>&1 || { cat "$work/build.log"; echo "fuzz: build failed"; exit 1; }
[ -x "$tool/sharpfuzz" ] || dotnet tool install --tool-path "$tool" SharpFuzz.CommandLine --version 2.3.0 >"$work/tool.log" 2>&1 \
  || { cat "$work/tool.log"; echo "fuzz: could not install SharpFuzz.CommandLine"; exit 1; }
bin="$work/bin"; rm -rf "$bin"; cp -r fuzz/SpectralRenderer.Fuzz/bin/Release/net10.0 "$bin"
"$tool/sharpfuzz" "$bin/SpectralRenderer.dll" >"$work/instrument.log" 2>&1 || { cat "$work/instrument.log"; echo "fuzz: instrumentation failed"; exit 1; }

export AFL_SKIP_BIN_CHECK=1 AFL_NO_UI=1 AFL_SKIP_CPUFREQ=1 AFL_I_DONT_CARE_ABOUT_MISSING_CRASHES=1 AFL_NO_AFFINITY=1
failed=0
for t in "${targets[@]}"; do
  out="$work/out-$t"; rm -rf "$out"
  timeout $((seconds + 60)) afl-fuzz -i "fuzz/seeds/$t" -o "$out" -V "$seconds" -t 5000 -m none -- dotnet "$bin/SpectralRenderer.Fuzz.dll" "$t" >"$work/afl-$t.log" 2>&1
  stats="$out/default/fuzzer_stats"
  if [ ! -f "$stats" ]; then tail -20 "$work/afl-$t.log"; echo "fuzz $t: afl-fuzz did not run"; failed=1; continue; fi
  get() { grep "^$1 " "$stats" | sed 's/.*: //'; }
  crashes=$(get saved_crashes); hangs=$(get saved_hangs)
  echo "fuzz $t: $(get execs_done) runs in $(get run_time) s, $(get corpus_count) paths, $(get edges_found) edges, $crashes crashes, $hangs hangs"
  if [ "${crashes:-0}" != 0 ] || [ "${hangs:-0}" != 0 ]; then
    failed=1
    ls "$out"/default/crashes/id* "$out"/default/hangs/id* 2>/dev/null | sed 's/^/  finding: /'
  fi
done
[ "$failed" = 0 ] && echo "fuzz: no crash or hang in ${#targets[@]} targets × ${seconds} s (findings and corpora in $work)"
exit $failed
