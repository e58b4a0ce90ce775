#!/usr/bin/env bash
# The benchmark's Python packages (bench/requirements.txt: flip-evaluator, numpy,
# matplotlib from PyPI) in .venv-bench, made once; prints nothing when already there.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv-bench
if [ ! -x "$venv/bin/python" ]; then
  echo "bench-deps: creating $venv"
  python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import flip_evaluator, numpy, matplotlib" 2>/dev/null; then
  "$venv/bin/pip" install -q --disable-pip-version-check -r bench/requirements.txt
fi
