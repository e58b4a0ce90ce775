#!/usr/bin/env bash
# The soak: 10,000 frames of the default scene at 320x180 on orbit and fly-through, T a square
# wave between a quarter and three quarters of the full-RT stage cost, a competing CPU load a
# quarter of the time, validation on. Prints memory growth after the warm-up (host RSS and
# device memory), non-finite values found in images and selection records, and adherence.
#   bash scripts/soak.sh [FRAMES] [extra raybudget soak options]
# (The test suite runs a 400-frame version: soak.short_run_keeps_memory_flat_and_values_finite.)
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-10000}
shift || true
bash scripts/build.sh
./build/tools/raybudget soak data/default/court.gltf --frames "$frames" --validation "$@"
