#!/usr/bin/env bash
# Fuzzes the glTF loader with libFuzzer (clang) under ASan + UBSan for SECONDS (default 60):
#   bash scripts/fuzz.sh [SECONDS]
# Seeds: the default scene (.gltf with its .bin, and as .glb) and a one-triangle file. A
# finding stops the run with the input saved in build-fuzz/run/ (crash-*, timeout-*, oom-*).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
bash scripts/setup-deps.sh  # clang and its libFuzzer runtime among them
if [ ! -f build-fuzz/build.ninja ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRAYBUDGET_FUZZ=ON -DRAYBUDGET_BUILD_TESTS=OFF
fi
cmake --build build-fuzz --target gltf_fuzzer
work=build-fuzz/run
mkdir -p "$work/corpus" "$work/seeds"
cp data/default/court.gltf data/default/court.bin "$work/"
cp data/default/court.gltf "$work/seeds/"
python3 - "$work/seeds" <<'PY'
import json, struct, sys
out = sys.argv[1]
doc = json.load(open("data/default/court.gltf"))
binary = open("data/default/court.bin", "rb").read()
del doc["buffers"][0]["uri"]
text = json.dumps(doc).encode()
text += b" " * (-len(text) % 4)
binary += b"\0" * (-len(binary) % 4)
chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary
open(f"{out}/court.glb", "wb").write(b"glTF" + struct.pack("<II", 2, 12 + len(chunks)) + chunks)
tri = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
       "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
       "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                     {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
       "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
       "buffers": [{"byteLength": 44, "uri": "triangle.bin"}]}
open(f"{out}/triangle.gltf", "w").write(json.dumps(tri))
# its buffer beside the inputs the harness writes (the working directory)
tri_bin = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"
open(f"{out}/../triangle.bin", "wb").write(tri_bin)
PY
cd "$work"
echo "fuzz: $seconds s of the glTF loader"
../gltf_fuzzer -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=65536 -print_final_stats=1 corpus seeds
