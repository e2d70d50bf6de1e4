#!/usr/bin/env bash
# Runs a sweep, interrupts it with SIGINT after AFTER jobs finished, resumes it, and checks that every job of the plan
# was rendered exactly once and is listed once, done, in the index (BENCHMARKS.md records the 200-job run).
#   usage: scripts/sweep-interrupt-resume.sh PLAN.json OUTDIR [AFTER=60]     (SPECTRAL: the command, default `spectral`)
set -euo pipefail
plan="$1" out="$2" after="${3:-60}"
read -r -a spectral <<< "${SPECTRAL:-spectral}"
rm -rf "$out"
done_count() { find "$out/jobs" -name job.json 2>/dev/null | wc -l; }
start=$(date +%s)
# Job control on: without it bash starts background commands with SIGINT ignored, and the interrupt would not arrive.
set -m
"${spectral[@]}" sweep "$plan" -o "$out" 2> "$out.first.log" &
pid=$!
while [ "$(done_count)" -lt "$after" ] && kill -0 "$pid" 2>/dev/null; do sleep 0.05; done
kill -INT "$pid"
set +e; wait "$pid"; code=$?; set -e
set +m
first=$(done_count)
echo "interrupted with SIGINT after $first jobs (exit $code): $(tail -n 1 "$out.first.log")"
# Each finished job's job.json (its finished_utc) before the resume: they must be unchanged after it.
find "$out/jobs" -name job.json -exec md5sum {} + | sort > "$out.before"
"${spectral[@]}" sweep "$plan" -o "$out" 2> "$out.second.log"
echo "resumed: $(tail -n 1 "$out.second.log")"
find "$out/jobs" -name job.json -exec md5sum {} + | sort > "$out.after"
comm -23 "$out.before" "$out.after" | grep . && { echo "a job finished before the interrupt was rendered again"; exit 1; }
python3 - "$out" "$first" <<'PY'
import json, os, sys
out, first = sys.argv[1], int(sys.argv[2])
rows = [json.loads(l) for l in open(os.path.join(out, "index.jsonl"))]
ids = [r["job"] for r in rows]
assert len(ids) == len(set(ids)), "a job is listed twice"
assert ids == sorted(ids) and all(r["status"] == "done" for r in rows), "a job is not done"
for r in rows: assert os.path.exists(os.path.join(out, r["path"], "render.json")), r
print(f"index: {len(rows)} jobs, each once, all done; {first} before the interrupt were not rendered again, {len(rows) - first} after it")
PY
echo "total $(( $(date +%s) - start )) s"
