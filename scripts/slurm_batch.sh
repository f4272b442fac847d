#!/usr/bin/env bash
#SBATCH --job-name=xparam-batch
#SBATCH --array=0-3
#SBATCH --cpus-per-task=4
#SBATCH --output=xparam-batch-%A_%a.log
#
# `xparam batch` on a Slurm cluster: a job array runs one shard per task, then a job that
# depends on the whole array merges the shard archives (the merged datasets are identical to
# those of a single run over all targets).
#
#   scripts/slurm_batch.sh [--xparam PATH] submit
#                                   on the login node: submits the array (0..N-1, N = XPARAM_SHARDS)
#                                   and the merge job (--dependency=afterany on the array); the jobs
#                                   run the xparam found here (exported to them as XPARAM)
#   scripts/slurm_batch.sh          inside array task i (SLURM_ARRAY_TASK_ID=i): runs shard i/N
#   scripts/slurm_batch.sh merge    merges ARCHIVE.h5.shards/shard_*.h5 into ARCHIVE.h5
#
# Configuration (environment; exported into the jobs by sbatch):
#   XPARAM_TEMPLATE, XPARAM_TEMPLATE_ANCHORS, XPARAM_TARGETS, XPARAM_OUT   required
#   XPARAM_CURVES        feature curves of the template (optional)
#   XPARAM_MEASUREMENTS  measurements of the template (optional, docs/measurements.md)
#   XPARAM_SHARDS        N (default: SLURM_ARRAY_TASK_COUNT inside a task, else 4 like --array above)
#   XPARAM_THREADS       -j of each shard (default: SLURM_CPUS_PER_TASK, else 1)
#   XPARAM_OPTIONS       further options of `xparam batch` for every shard, split at spaces
#                        (e.g. "--no-optimize-map --max-maps 3")
#   XPARAM               the xparam program (default: --xparam PATH, else `xparam` on PATH, else
#                        this checkout's build/src/cli/xparam)
# A shard runs with --resume: resubmitting after a node failure completes only what is missing.
# The array uses afterany, not afterok: a shard with failed targets exits 2 (they are recorded
# in its archive) and must still be merged.
set -euo pipefail

explicit=
if [[ ${1:-} == --xparam ]]; then
  explicit=${2:?slurm_batch.sh: --xparam needs a path}
  shift 2
fi
# Inside a job Slurm runs a copy of this file from its spool folder: the finder beside it is
# found only on the login node, and the jobs get its answer as XPARAM (sbatch --export=ALL).
here=$(dirname "${BASH_SOURCE[0]}")
if [[ -f $here/find_xparam.sh ]]; then
  source "$here/find_xparam.sh"
  find_xparam slurm_batch.sh "$explicit"
else
  xparam=${explicit:-${XPARAM:-xparam}}
fi
export XPARAM=$xparam
require() {
  local name=$1
  [[ -n ${!name:-} ]] || { echo "slurm_batch.sh: set $name" >&2; exit 1; }
}
require XPARAM_OUT
shard_dir="$XPARAM_OUT.shards"
shards=${XPARAM_SHARDS:-${SLURM_ARRAY_TASK_COUNT:-4}}
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "slurm_batch.sh: XPARAM_SHARDS must be a positive integer" >&2; exit 1; }

run_shard() {
  require XPARAM_TEMPLATE
  require XPARAM_TEMPLATE_ANCHORS
  require XPARAM_TARGETS
  local task=${SLURM_ARRAY_TASK_ID:?slurm_batch.sh: not inside an array task (SLURM_ARRAY_TASK_ID unset)}
  if [[ -n ${SLURM_ARRAY_TASK_COUNT:-} && $SLURM_ARRAY_TASK_COUNT != "$shards" ]]; then
    echo "slurm_batch.sh: the array has $SLURM_ARRAY_TASK_COUNT tasks but XPARAM_SHARDS=$shards" >&2
    exit 1
  fi
  local options=(--template "$XPARAM_TEMPLATE" --template-anchors "$XPARAM_TEMPLATE_ANCHORS"
                 --targets "$XPARAM_TARGETS" -j "${XPARAM_THREADS:-${SLURM_CPUS_PER_TASK:-1}}"
                 --resume --shard "$task/$shards" --out "$shard_dir/shard_$task.h5"
                 --summary "$shard_dir/shard_$task.summary.json")
  [[ -n ${XPARAM_CURVES:-} ]] && options+=(--curves "$XPARAM_CURVES")
  [[ -n ${XPARAM_MEASUREMENTS:-} ]] && options+=(--measurements "$XPARAM_MEASUREMENTS")
  if [[ -n ${XPARAM_OPTIONS:-} ]]; then
    local extra
    read -ra extra <<< "$XPARAM_OPTIONS"
    options+=("${extra[@]}")
  fi
  mkdir -p "$shard_dir"
  exec "$xparam" batch "${options[@]}"
}

run_merge() {
  local files=()
  for ((i = 0; i < shards; ++i)); do
    [[ -f $shard_dir/shard_$i.h5 ]] || { echo "slurm_batch.sh: shard $i has no archive ($shard_dir/shard_$i.h5)" >&2; exit 3; }
    files+=("$shard_dir/shard_$i.h5")
  done
  exec "$xparam" merge "${files[@]}" --force --out "$XPARAM_OUT"
}

submit() {
  local array_id
  array_id=$(sbatch --parsable --export=ALL --array="0-$((shards - 1))" "$0")
  array_id=${array_id%%;*}  # --parsable prints "id" or "id;cluster"
  # --wrap: the merge job must not read this file's #SBATCH --array line.
  sbatch --parsable --export=ALL --dependency="afterany:$array_id" --job-name=xparam-merge \
    --output="xparam-merge-%j.log" --wrap="$(printf '%q ' "$(realpath "$0")" merge)"
  echo "slurm_batch.sh: submitted array $array_id ($shards shards) and its merge" >&2
}

case ${1:-} in
  submit) submit ;;
  merge) run_merge ;;
  "") run_shard ;;
  *) echo "slurm_batch.sh: unknown mode '$1' (submit, merge, or none inside an array task)" >&2; exit 1 ;;
esac
