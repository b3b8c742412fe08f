#!/usr/bin/env bash
# A sweep as a Slurm job array: task k of N runs shard k/N of the sweep file with as many render
# threads as the task has CPUs (docs/sweeps.md). Every task writes its records into the same folder
# (a shared file system); merge them once all tasks are done:
#   sbatch --array=1-8 scripts/slurm-sweep.sh bench/tradeoffs.sweep.yaml --out /shared/tradeoffs
#   shadowref sweep bench/tradeoffs.sweep.yaml --out /shared/tradeoffs --merge
# A task that was cut short is simply submitted again: finished jobs are skipped. The array must be
# a plain range (1-8, 0-15), not one with steps or a list. Arguments after the sweep file go to
# `shadowref sweep`. SHADOWREF names the program (default: shadowref on PATH, else build/shadowref).
#SBATCH --job-name=shadowref-sweep
#SBATCH --array=1-8
#SBATCH --cpus-per-task=2
#SBATCH --mem-per-cpu=1G
#SBATCH --time=02:00:00
#SBATCH --output=slurm-sweep-%A_%a.out
set -euo pipefail

if [ $# -lt 1 ]; then
  echo "usage: sbatch --array=1-N scripts/slurm-sweep.sh SPEC [shadowref sweep options...]" >&2
  exit 2
fi
spec=$1
shift
if [ -z "${SLURM_ARRAY_TASK_ID:-}" ] || [ -z "${SLURM_ARRAY_TASK_COUNT:-}" ]; then
  echo "slurm-sweep: not a task of a Slurm job array (SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_COUNT unset);" \
       "submit with: sbatch --array=1-N $0 $spec" >&2
  exit 2
fi
# Slurm numbers the tasks from the array's first index (often 1, sometimes 0); shards count from 1.
shard=$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-1} + 1))
count=$SLURM_ARRAY_TASK_COUNT
threads=${SLURM_CPUS_PER_TASK:-1}
shadowref=${SHADOWREF:-}
if [ -z "$shadowref" ]; then
  shadowref=$(command -v shadowref || echo build/shadowref)
fi
echo "slurm-sweep: $shadowref sweep $spec --shard $shard/$count --threads $threads $*" >&2
exec "$shadowref" sweep "$spec" --shard "$shard/$count" --threads "$threads" "$@"
