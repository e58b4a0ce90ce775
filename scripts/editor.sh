#!/usr/bin/env bash
# The level editor: builds what it needs, then opens SCENE (default: the bundled court) in
# raybudget-editor. Extra arguments go to the editor (raybudget-editor --help). Without a
# display it runs under Xvfb, where only --script and --screenshot are of use.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
scene=data/default/court.gltf
if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then
  scene=$1
  shift
fi
if [ -z "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  echo "editor.sh: no display; running under xvfb-run" >&2
  exec xvfb-run -a -s "-screen 0 1920x1080x24" ./build/editor/raybudget-editor "$scene" "$@"
fi
exec ./build/editor/raybudget-editor "$scene" "$@"
