#!/usr/bin/env bash
# Set up (packages, configure, build) and run every test. Usage: scripts/test.sh [BUILD_DIR] [extra cmake args...]
# XPARAM_TEST_LABELS_EXCLUDED='slow|real_data' leaves out the long cases on the bundled data and on
# ../shared/data (a ctest -LE regular expression).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
shift || true
"$root/scripts/setup.sh" "$build" -DXPARAM_BUILD_TESTS=ON "$@"
exclude=()
[[ -n "${XPARAM_TEST_LABELS_EXCLUDED:-}" ]] && exclude=(-LE "$XPARAM_TEST_LABELS_EXCLUDED")
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "${exclude[@]}"
