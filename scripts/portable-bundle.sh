#!/usr/bin/env bash
# Packs the built programs with the libraries Debian 12 gave them, so the tests and
# benchmarks run on another x86-64 Linux machine with a Vulkan driver but none of our
# packages (how the GPU figures in docs/ were taken): build/portable.tar.xz holds bin/
# (stripped), lib/ (Embree, TBB, OpenEXR, tinygltf, stb, the Vulkan loader), layers/ (the
# Khronos validation layer) and env.sh, which points LD_LIBRARY_PATH and VK_LAYER_PATH there.
# On the target: tar -xJf portable.tar.xz -C DIR && . DIR/env.sh && DIR/bin/select_bench
# The tests find data/ and ../shared/scenes at the paths compiled in (this checkout's):
# link a copy of the checkout (and of ../shared) there, or they skip the shared scenes.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
out=build/portable
rm -rf "$out" && mkdir -p "$out/bin" "$out/lib" "$out/layers"
for program in tools/raybudget tests/render_tests tests/scene_tests bench/select_bench bench/tracer_bench bench/frame_bench; do
  strip -o "$out/bin/$(basename "$program")" "build/$program"
done
# Every library the programs load from outside the C runtime and the GPU driver.
for program in "$out"/bin/*; do ldd "$program"; done | awk '/=> \// {print $3}' | sort -u |
  grep -Ev '/(libc|libm|libstdc\+\+|libgcc_s|libz|ld-linux[^/]*)\.so' | while read -r library; do cp -L "$library" "$out/lib/"; done
cp /usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so "$out/layers/"
sed 's#"library_path": *"[^"]*"#"library_path": "./libVkLayer_khronos_validation.so"#' \
  /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json >"$out/layers/VkLayer_khronos_validation.json"
cat >"$out/env.sh" <<'EOF'
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" VK_LAYER_PATH="$here/layers"
EOF
tar -C "$out" -cJf build/portable.tar.xz .
echo "build/portable.tar.xz: $(du -h build/portable.tar.xz | cut -f1)"
