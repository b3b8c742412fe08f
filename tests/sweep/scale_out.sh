#!/usr/bin/env bash
# A sweep scaled out (docs/sweeps.md): a tiny sweep file run unsharded, as 3 shards by GNU
# parallel, and as a 3-task Slurm array (scripts/slurm-sweep.sh with the SLURM_* variables a job
# array sets), each merged: the three CSVs are the same bytes. Then one timed shard: its rows name
# this machine (hostname, CPU model, threads). Exit 77 (skipped) without GNU parallel.
#   tests/sweep/scale_out.sh BUILD/shadowref      (run from the source folder)
set -euo pipefail
shadowref=$1
command -v parallel >/dev/null || { echo "scale_out: GNU parallel is not installed (scripts/setup.sh --role test)"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
spec=$work/tiny.sweep.yaml
scenes=$(pwd)/scenes
cat > "$spec" <<YAML
record: [error, counts, time]
repetitions: 1
set: {image.width: 24, image.height: 16}
groups:
  - {name: volumes, scenes: [$scenes/room.yaml, $scenes/two_lights.yaml], methods: [none, zpass, zfail, auto]}
  - name: maps
    scenes: [$scenes/outdoor.yaml]
    methods: [shadowmap, tsm]
    grid: {shadow.map_size: [64, 128]}
YAML
jobs=$("$shadowref" sweep "$spec" --list | wc -l)
[ "$jobs" -eq 12 ] || { echo "scale_out: expected 12 jobs, --list printed $jobs"; exit 1; }

# One process, every job.
"$shadowref" sweep "$spec" --no-timing --out "$work/one" 2>/dev/null
"$shadowref" sweep "$spec" --out "$work/one" --merge --csv "$work/one.csv" 2>/dev/null

# GNU parallel, three shards at once (the recipe of docs/sweeps.md).
parallel "$shadowref" sweep "$spec" --no-timing --out "$work/par" --shard {}/3 ::: 1 2 3 2>/dev/null
"$shadowref" sweep "$spec" --out "$work/par" --merge --csv "$work/par.csv" 2>/dev/null
cmp "$work/one.csv" "$work/par.csv" || { echo "scale_out: GNU parallel's merged CSV differs from the unsharded run's"; exit 1; }
[ "$(ls "$work/par"/*.json | wc -l)" -eq 12 ] || { echo "scale_out: the shards did not write 12 records"; exit 1; }

# The Slurm array script, each task as Slurm would start it.
for task in 1 2 3; do
  SLURM_ARRAY_TASK_ID=$task SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_COUNT=3 SLURM_CPUS_PER_TASK=2 \
    SHADOWREF=$shadowref bash scripts/slurm-sweep.sh "$spec" --no-timing --out "$work/slurm" 2>"$work/slurm-$task.err"
  # Task k ran shard k/3 and nothing else, with the allocation's threads.
  grep -q "shard $task/3: " "$work/slurm-$task.err" || { echo "scale_out: task $task did not run shard $task/3"; cat "$work/slurm-$task.err"; exit 1; }
  grep -q -- "--threads 2" "$work/slurm-$task.err" || { echo "scale_out: task $task did not take --threads from SLURM_CPUS_PER_TASK"; exit 1; }
  expected=$("$shadowref" sweep "$spec" --list --shard "$task/3" | wc -l)
  [ "$(ls "$work/slurm"/*.json | wc -l)" -eq $((prev = ${prev:-0} + expected)) ] || { echo "scale_out: task $task wrote the wrong records"; exit 1; }
done
"$shadowref" sweep "$spec" --out "$work/slurm" --merge --csv "$work/slurm.csv" 2>/dev/null
cmp "$work/one.csv" "$work/slurm.csv" || { echo "scale_out: the Slurm array's merged CSV differs from the unsharded run's"; exit 1; }
# Outside a job array the script refuses to guess a shard.
if bash scripts/slurm-sweep.sh "$spec" --out "$work/none" 2>/dev/null; then echo "scale_out: slurm-sweep.sh ran outside an array"; exit 1; fi

# Timed: one shard of two, by parallel; the rows it timed carry this machine, the others no time.
parallel "$shadowref" sweep "$spec" --out "$work/timed" --threads 1 --shard {}/2 ::: 1 2>/dev/null
"$shadowref" sweep "$spec" --out "$work/timed" --no-timing --shard 2/2 2>/dev/null
"$shadowref" sweep "$spec" --out "$work/timed" --merge --csv "$work/timed.csv" --plots "$work/plots" 2>/dev/null
cpu=$(sed -n 's/^model name[[:space:]]*: *//p' /proc/cpuinfo | head -1)
python3 - "$work/timed.csv" "$(hostname)" "$cpu" "$("$shadowref" sweep "$spec" --list --shard 1/2 | sed 's/.*"id":"\([0-9a-f]*\)".*/\1/' | tr '\n' ' ')" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
host, cpu, timed = sys.argv[2], sys.argv[3], set(sys.argv[4].split())
assert len(rows) == 12, len(rows)
for r in rows:
    if r["id"] in timed:
        assert r["hostname"] == host and r["cpu"] == (cpu or "unknown") and r["threads"] == "1", r
        assert float(r["time_ms"]) > 0 and float(r["cpu_ms"]) >= 0 and r["repetitions"] == "1", r
        assert r["build"].startswith("shadowref "), r
    else:
        assert r["hostname"] == r["time_ms"] == r["cpu"] == "", r
PY
# Each plot's data names every timed point of it by its configuration.
for dat in "$work"/plots/plot-*.dat; do
  grep -q '"' "$dat" || { echo "scale_out: $dat has no labelled point"; exit 1; }
done
echo "scale_out: 12 jobs; unsharded, GNU parallel and Slurm array merged to the same CSV; timings name $(hostname)"
