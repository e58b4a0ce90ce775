#!/usr/bin/env bash
# The whole test suite: installs and builds what it needs, then runs CTest twice:
#  1. the CPU tests built with ASan + UBSan (the sanitizer build has only them): scene loading,
#     bad input, round trips, and the CPU references the GPU tests trust (BVH traversal, the
#     selection policies, the cost model);
#  2. the glTF loader under libFuzzer (clang, ASan + UBSan) for FUZZ_SECONDS (default 60);
#  3. everything in the normal build: every GPU test runs with the Khronos validation
#     layers on, and any validation message fails it; and the benchmark on a tiny sweep.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-deps.sh
bash scripts/bench-deps.sh  # bench.tiny_sweep_end_to_end: bench/run.py's Python packages
BUILD_DIR=build-asan CMAKE_ARGS="-DRAYBUDGET_SANITIZE=ON" bash scripts/build.sh --target scene_tests
(cd build-asan && ctest --output-on-failure --timeout 900 -j"${TEST_JOBS:-2}")
bash scripts/fuzz.sh "${FUZZ_SECONDS:-60}"
bash scripts/build.sh
cd build
ctest --output-on-failure --timeout 900 -j"${TEST_JOBS:-2}" "$@"
