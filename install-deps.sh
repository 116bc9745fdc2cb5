#!/usr/bin/env bash
# Installs the Debian packages libroma needs, only those that are missing.
# Usage: ./install-deps.sh [--with-viewer-test]   (root, or sudo when available)
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  mesa-vulkan-drivers libvulkan-dev vulkan-validationlayers glslang-tools
  libglfw3-dev libembree-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libtinyexr-dev libcjson-dev
  clang libclang-rt-14-dev
  libimgui-dev xvfb xauth
  doxygen dpkg-dev
  gnuplot-nox
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  run=()
elif command -v sudo >/dev/null 2>&1; then
  run=(sudo)
else
  echo "install-deps: need root or sudo to install: ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${run[@]}" apt-get update -q
"${run[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
