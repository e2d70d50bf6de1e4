#!/usr/bin/env bash
# Shards and a sweep through a real one-node Slurm (cluster.sh): a 4-task array renders the four shards of a scene,
# `spectral merge` assembles them, and every file is compared with a single-process render byte for byte
# (render.json without created_utc, timings_s, rays.mrays_per_s, threads and run); then a 4-task array runs a sweep emitted
# by `spectral sweep --emit slurm` and its index must list every job once, done. Stops the daemons on exit.
#   usage: tests/slurm/ci.sh SPECTRAL_DLL WORKDIR       (SHARD_SIZE, default 128, sets the renders' size;
#                                                       with SPECTRAL_MODELS holding stanford-bunny.obj the §3.2 bunny is sharded too)
# Exit 0: passed; 1: a check failed; 3: no Slurm here (the reason is printed).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
dll="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
work="$2"
size="${SHARD_SIZE:-128}"
spectral() { dotnet "$dll" "$@"; }

rm -rf "$work" && mkdir -p "$work"
export SPECTRAL_SLURM_RUN="$work/cluster"
trap '"$here/cluster.sh" stop >/dev/null 2>&1 || true' EXIT
eval "$("$here/cluster.sh" start)"

same_render() {  # same_render EXPECTED ACTUAL
  local a="$1" b="$2"
  diff <(cd "$a" && find . -type f | sort) <(cd "$b" && find . -type f | sort) || { echo "file lists differ: $a $b"; return 1; }
  (cd "$a" && find . -type f ! -name render.json | sort) | while read -r f; do
    cmp -s "$a/$f" "$b/$f" || { echo "$f differs between $a and $b"; return 1; }
  done
  python3 - "$a/render.json" "$b/render.json" <<'PY'
import json, sys
def load(p):
    m = json.load(open(p))
    for k in ("created_utc", "timings_s", "threads", "run"): m.pop(k, None)
    m["rays"].pop("mrays_per_s", None)
    return m
a, b = (load(p) for p in sys.argv[1:3])
sys.exit(0 if a == b else "render.json differs beyond the run fields")
PY
}

shard_scene() {  # shard_scene NAME SCENE [render options…]
  local name="$1" scene="$2"; shift 2
  local dir="$work/$name"
  mkdir -p "$dir"
  spectral render "$scene" -o "$dir/single" --quiet "$@"
  # Each array task finds its shard in SLURM_ARRAY_TASK_ID/_MIN/_MAX/_STEP: no --shard on the command line.
  cat > "$dir/shards.sbatch" <<SB
#!/bin/bash
#SBATCH --array=0-3
#SBATCH --output=$dir/slurm-%A_%a.out
#SBATCH --cpus-per-task=1
exec dotnet "$dll" render "$scene" -o "$dir/shard-\$SLURM_ARRAY_TASK_ID" --threads 1 $*
SB
  sbatch --wait "$dir/shards.sbatch" >/dev/null || { cat "$dir"/slurm-*.out; echo "the $name shard array failed"; return 1; }
  for i in 0 1 2 3; do grep -q "\"shard\": \"$i/4 (Slurm)\"" "$dir/shard-$i/render.json" || { echo "shard $i did not take its index from Slurm"; return 1; }; done
  spectral merge "$dir"/shard-* -o "$dir/merged" --quiet
  same_render "$dir/single" "$dir/merged"
  echo "slurm: 4 shards of $name (${size}²) merged = the single render, byte for byte"
}

shard_scene glass-mirror "$repo/scenes/glass-mirror.json" --width "$size" --height "$size"
if [ -n "${SPECTRAL_MODELS:-}" ] && [ -f "$SPECTRAL_MODELS/stanford-bunny.obj" ]; then
  shard_scene bunny "$repo/scenes/paper-3.2-bunny-19.json" --width "$size" --height "$size" --models "$SPECTRAL_MODELS"
else
  echo "slurm: the §3.2 bunny is skipped: SPECTRAL_MODELS does not hold stanford-bunny.obj"
fi

# A sweep as a 4-task array: the script `spectral sweep --emit slurm` writes, submitted as it is.
plan="$work/sweep/plan.json"
mkdir -p "$work/sweep"
cat > "$plan" <<'JSON'
{ "scene": "REPO/scenes/glass-mirror.json",
  "set": { "camera.width": 48, "camera.height": 32, "camera.spp": 1, "max_depth": 2 },
  "formats": ["npy", "png"],
  "axes": [ { "name": "patch", "path": "materials.red.diffuse", "values": ["colorchecker:1", "colorchecker:2", "colorchecker:3", "colorchecker:4", "colorchecker:5"] },
            { "name": "light", "path": "lights[0].spectrum", "values": ["D65", "A"] } ],
  "extra": [ { "name": "bands-31", "set": { "bands": "400:700:31" } } ] }
JSON
sed -i "s#REPO#$repo#" "$plan"
spectral sweep "$plan" -o "$work/sweep/out" --emit slurm --shards 4 --quiet
sbatch --wait "$work/sweep/out/sweep.sbatch" >/dev/null || { cat "$work"/sweep/out/logs/*.out; echo "the sweep array failed"; exit 1; }
python3 - "$work/sweep/out" <<'PY'
import json, os, sys
out = sys.argv[1]
rows = [json.loads(l) for l in open(os.path.join(out, "index.jsonl"))]
ids = [r["job"] for r in rows]
assert ids == [f"{i:04d}" for i in range(11)], ids
assert all(r["status"] == "done" for r in rows), [r for r in rows if r["status"] != "done"]
assert all(os.path.exists(os.path.join(out, r["path"], "render.json")) for r in rows)
PY
echo "slurm: a 4-task sweep array rendered all 11 jobs, each listed once in the index"
# Resubmitted, the array finds every job done and renders none.
again=$(sbatch --parsable --wait "$work/sweep/out/sweep.sbatch")
[ "$(grep -l -- "— 0 rendered, [0-9]* already done" "$work/sweep/out/logs/${again%%;*}"_*.out | wc -l)" = 4 ] \
  || { cat "$work/sweep/out/logs/${again%%;*}"_*.out; echo "a resubmitted sweep rendered jobs again"; exit 1; }
echo "slurm: resubmitted, the sweep array rendered no job twice"
