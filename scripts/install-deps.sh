#!/usr/bin/env bash
# Installs what saagen needs from Debian bookworm's packages, and nothing that is already there.
# Safe to run repeatedly; needs root (or sudo) only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  glslang-dev spirv-tools spirv-headers
  # Debian's glslang CMake config names /usr/bin/glslangValidator as an imported target and
  # fails without it; saagen compiles in-process and never runs the tool.
  glslang-tools
  # shaderc: the include handler for engines that compile with shaderc (saagen::shaderc)
  libshaderc-dev
  libvulkan-dev mesa-vulkan-drivers
  # Khronos validation layer: every GPU test runs with it on (SAAGEN_VK_VALIDATION=1)
  vulkan-validationlayers
  libcli11-dev nlohmann-json3-dev libfmt-dev libstb-dev libtomlplusplus-dev
  libgtest-dev libgmock-dev librapidcheck-dev libbenchmark-dev
  # glTF 2.0 assets as trade scenes (measure/gltf.hpp: `saagen bench --scene ASSET`),
  # and content nobody here authored: Khronos's CC-BY 4.0 sample models ClearCoatTest and
  # 2CylinderEngine under /usr/share/assimp/models/glTF2/ (tests/measure/test_gltf_assets.cpp)
  libtinygltf-dev assimp-testmodels
  # assimp's command-line tool converts assimp-testmodels' other formats to glTF: the held-out
  # models the table-free advice is reported on (scripts/held_out.sh)
  assimp-utils
  # the CC0 tangent-space normal maps of the npm package @pmndrs/assets (package.json) are WebP
  # images: libwebp decodes them for the presets' pmndrs-NNNN scenes (measure/assets.hpp),
  # webp's dwebp for scripts/normal_map_sphere.py
  libwebp-dev webp
  # the report test opens the generated HTML report in headless Chromium; chromium also ships
  # SwiftShader (/usr/lib/chromium/vk_swiftshader_icd.json), the second Vulkan device of the GPU tests
  chromium
  # clang: test.sh compiles the library and CLI with it too, so that scripts/sanitize.sh and
  # scripts/fuzz.sh (clang's sanitizers and libFuzzer) cannot break unseen
  clang
  # clang-format: ctest's format_check (scripts/format_check.sh) holds the sources to .clang-format
  clang-format
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$package")
  fi
done

# Node.js and npm for the WebGL2 tests of the GLSL ES target, the three.js example and the WGSL
# target's WebGPU runs (puppeteer-core, three and webgpu, i.e. Dawn for Node, from the npm
# registry, pinned by package-lock.json; npm ci below, no browser download). Debian's packages
# only where no node/npm is on the PATH: a Node.js from another source (e.g. NodeSource's
# nodejs, which bundles npm and conflicts with Debian's npm) is used as it is.
if ! command -v node > /dev/null || ! command -v npm > /dev/null; then
  missing+=(nodejs npm)
fi

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  echo "install-deps: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# npm packages exactly as package-lock.json pins them, when node_modules is missing or older than
# the lockfile. puppeteer-core downloads no browser (the tests use /usr/bin/chromium);
# --ignore-scripts runs no package's install scripts. webgpu ships its prebuilt Dawn for Node
# addon (dist/linux-x64/dawn.node) inside the package, so it needs none: its postinstall only
# clears macOS's quarantine attribute. harness/webgpu runs it on SwiftShader's Vulkan ICD, which
# the chromium package above installs.
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ ! -f "$root/node_modules/.package-lock.json" ] || [ "$root/package-lock.json" -nt "$root/node_modules/.package-lock.json" ]; then
  echo "install-deps: npm ci in $root"
  (cd "$root" && PUPPETEER_SKIP_DOWNLOAD=1 npm ci --ignore-scripts --no-audit --no-fund)
else
  echo "install-deps: node_modules matches package-lock.json"
fi
