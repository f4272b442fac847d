#!/usr/bin/env bash
# Run `xparam batch` over a dataset folder as N shards with GNU parallel, then merge the shard
# archives into one (its datasets are identical to those of a single run over the folder).
#
# Usage:
#   scripts/run_parallel.sh [--xparam PATH] SHARDS ARCHIVE.h5 XPARAM_BATCH_OPTIONS...
# e.g.
#   scripts/run_parallel.sh 4 out/all.h5 --template tests/data/human_man.obj \
#       --template-anchors tests/data/human.anchors.json --targets tests/data/sample_targets -j 1
#
# Shard i writes ARCHIVE.h5.shards/shard_i.h5 (with --resume, so running the script again after
# an interruption only completes what is missing). Do not pass --out or --shard yourself.
# The xparam program: --xparam PATH, else $XPARAM, else `xparam` on PATH, else this checkout's
# build/src/cli/xparam. PARALLEL_JOBS: shards run at once (default: SHARDS).
# Exit status: that of xparam batch (0 all ok, 2 some targets failed, recorded in the archive);
# 3 when a shard or the merge failed fatally, 1 on a usage error.
set -euo pipefail

usage() {
  sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 1
}

source "$(dirname "${BASH_SOURCE[0]}")/find_xparam.sh"
explicit=
if [[ ${1:-} == --xparam ]]; then
  [[ $# -ge 2 ]] || usage
  explicit=$2
  shift 2
fi
[[ $# -ge 2 ]] || usage
shards=$1
out=$2
shift 2
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "run_parallel.sh: SHARDS must be a positive integer, got '$shards'" >&2; exit 1; }
for arg in "$@"; do
  case $arg in
    --out | --out=* | --shard | --shard=*) echo "run_parallel.sh: do not pass $arg; the script sets it" >&2; exit 1 ;;
  esac
done
command -v parallel >/dev/null || { echo "run_parallel.sh: GNU parallel is not installed" >&2; exit 3; }
find_xparam run_parallel.sh "$explicit"
jobs=${PARALLEL_JOBS:-$shards}

shard_dir="$out.shards"
mkdir -p "$shard_dir"
joblog="$shard_dir/joblog.txt"
rm -f "$joblog"

# -q quotes every word of the command, so options holding spaces survive; the job log gives
# each shard's own exit status (parallel's only counts failures).
set +e
parallel -q --will-cite --jobs "$jobs" --halt never --joblog "$joblog" --tag --line-buffer \
  "$xparam" batch "$@" --resume --shard "{}/$shards" --out "$shard_dir/shard_{}.h5" \
  ::: $(seq 0 $((shards - 1))) < /dev/null  # never wait on the caller's stdin
set -e

status=0
while IFS=$'\t' read -r _ _ _ _ _ _ exitval signal command; do
  if [[ $signal != 0 || ($exitval != 0 && $exitval != 2) ]]; then
    echo "run_parallel.sh: shard failed (exit $exitval, signal $signal): $command" >&2
    status=3
  elif [[ $exitval == 2 && $status == 0 ]]; then
    status=2
  fi
done < <(tail -n +2 "$joblog")
finished=$(($(wc -l < "$joblog") - 1))
if [[ $finished -ne $shards ]]; then
  echo "run_parallel.sh: $finished of $shards shards finished" >&2
  exit 3
fi
if [[ $status == 3 ]]; then
  echo "run_parallel.sh: not merging; rerun the script to resume the failed shards" >&2
  exit 3
fi

shard_files=()
for ((i = 0; i < shards; ++i)); do shard_files+=("$shard_dir/shard_$i.h5"); done
"$xparam" merge "${shard_files[@]}" --force --out "$out" || { echo "run_parallel.sh: merge failed" >&2; exit 3; }
echo "run_parallel.sh: $shards shards merged into $out" >&2
exit "$status"
