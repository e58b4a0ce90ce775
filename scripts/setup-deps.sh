#!/usr/bin/env bash
# Installs every Debian 12 package the build, the tests and the benchmarks need.
# Mesa comes from bookworm-backports (25.x): lavapipe there has Vulkan 1.4, descriptor
# indexing and VK_KHR_ray_query, and runs our compute 1.2-1.6x faster than Mesa 22.3.
# Idempotent and quick when everything is present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config git python3 python3-venv
  libvulkan-dev vulkan-validationlayers vulkan-tools spirv-tools
  glslang-tools glslang-dev
  libglfw3-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libimgui-dev
  libopenexr-dev libimath-dev
  libgtest-dev libgmock-dev
  libembree-dev
  xvfb xauth
  clang libclang-rt-14-dev
)

sudo_() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

backports=/etc/apt/sources.list.d/raybudget-bookworm-backports.sources
mesa_from_backports() {
  dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null | grep -q bpo
}

# Node.js runs the Khronos glTF-Validator, the loader's oracle (tests/validator).
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then missing+=(nodejs npm); fi
# The Khronos glTF-Validator (npm), the loader's oracle, into tests/validator.
install_validator() {
  local validator
  validator="$(dirname "$0")/../tests/validator"
  [ -d "$validator/node_modules/gltf-validator" ] && return 0
  echo "setup-deps: installing the glTF-Validator (npm) into tests/validator"
  npm install --prefix "$validator" --no-audit --no-fund --no-package-lock --silent ||
    echo "setup-deps: could not install the glTF-Validator; its test will be skipped"
}

if [ ${#missing[@]} -eq 0 ] && mesa_from_backports; then
  install_validator
  exit 0
fi

if [ ! -f "$backports" ] && ! grep -rqs 'bookworm-backports' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "setup-deps: adding the bookworm-backports suite (for Mesa 25.x lavapipe)"
  sudo_ tee "$backports" >/dev/null <<'SRC'
Types: deb
URIs: http://deb.debian.org/debian
Suites: bookworm-backports
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
fi

export DEBIAN_FRONTEND=noninteractive
echo "setup-deps: apt-get update"
sudo_ apt-get update -q
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup-deps: installing ${missing[*]}"
  sudo_ apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
if ! mesa_from_backports; then
  echo "setup-deps: installing mesa-vulkan-drivers from bookworm-backports"
  sudo_ apt-get install -y -q --no-install-recommends -t bookworm-backports mesa-vulkan-drivers
fi
install_validator
