#!/usr/bin/env bash
# The whole test suite: installs and builds what it needs, then runs CTest. Every GPU test
# runs with the Khronos validation layers on, and any validation message fails it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest --output-on-failure --timeout 900 -j"${TEST_JOBS:-2}" "$@"
