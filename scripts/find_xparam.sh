# Sourced by scripts/run_parallel.sh and scripts/slurm_batch.sh (not run on its own).
# find_xparam SCRIPT [EXPLICIT] sets $xparam to the absolute path of the xparam program to run:
# EXPLICIT (the script's --xparam PATH), else $XPARAM, else `xparam` on PATH, else the build of
# this checkout (build/src/cli/xparam, what scripts/setup.sh and scripts/demo.sh build). Exits 1
# naming SCRIPT when none is found.
find_xparam() {
  local script=$1 explicit=${2:-} root candidate
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  if [[ -n $explicit ]]; then
    candidate=$explicit
  elif [[ -n ${XPARAM:-} ]]; then
    candidate=$XPARAM
  elif command -v xparam > /dev/null; then
    candidate=$(command -v xparam)
  else
    candidate=$root/build/src/cli/xparam
  fi
  if [[ $candidate != */* ]]; then candidate=$(command -v "$candidate" || true); fi
  if [[ -z $candidate || ! -x $candidate ]]; then
    echo "$script: no xparam program (tried ${explicit:-${XPARAM:-xparam on PATH, then $root/build/src/cli/xparam}}):" \
      "build it with scripts/setup.sh, or pass --xparam PATH" >&2
    exit 1
  fi
  xparam=$(realpath "$candidate")
}
