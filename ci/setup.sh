#!/usr/bin/env bash
# Installs every system package sao needs. Idempotent and quiet when all is present;
# runs `apt-get update` only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  glslang-dev glslang-tools spirv-tools
  # codegen: SPIRV-Cross writes HLSL and GLSL ES 3.10 from the SPIR-V (its static C++ libraries)
  spirv-cross libspirv-cross-c-shared-dev
  libgtest-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  libegl-dev libgl-dev libegl1-mesa-dev libgl1-mesa-dri libepoxy-dev
  libglfw3-dev libglm-dev libopenexr-dev libimgui-dev
  # backends/core: Imath's half.h (header only) for the binary16 conversions
  libimath-dev
  libembree-dev libtbb-dev libstb-dev nlohmann-json3-dev
  # backends/cli/: the command line of the sample programs and the timing tools
  libcli11-dev
  # samples/scenes: glTF through tinygltf (its header); tests/scenes reads the malformed and real
  # models of assimp-testmodels (model files only, no assimp library)
  libtinygltf-dev assimp-testmodels
  xvfb xauth
  # tests/apps/viewer_keys.sh: short key presses into sao-viewer under Xvfb
  xdotool
  # ci/fuzz.sh: clang with libFuzzer and the sanitizer runtimes; llvm-symbolizer for the reports
  clang-14 libclang-rt-14-dev llvm-14
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "ci/setup.sh: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "ci/setup.sh: done"
