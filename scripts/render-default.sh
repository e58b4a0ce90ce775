#!/usr/bin/env bash
# The main job: renders the bundled default scene (data/default/court.gltf) at 1280x720 on
# an orbit of 60 frames, ray tracing the items (shadows, reflections, refractions) the benefit policy selects within a 200 ms
# ray-tracing budget (coverage + select + trace), and writes out/default/{frame.png, frame.exr, stats.csv}.
# Extra arguments go to `raybudget render` (e.g. --frames 10, --budget-ms 20, --policy paper).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/tools/raybudget render data/default/court.gltf --frames 60 --camera orbit --policy benefit --budget-ms 200 --out out/default "$@"
