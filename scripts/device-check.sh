#!/usr/bin/env bash
# Every GPU suite on one Vulkan device (SAAGEN_VK_DEVICE) and the 4K shading-cost table, in one
# call: the check a session runs when it is lent a real GPU (docs/GPU_TIMINGS.md).
#
#   bash scripts/device-check.sh build         # here (Debian bookworm, scripts/install-deps.sh):
#                                              #   build the GPU suites and benches, stage them
#                                              #   into device-check/ (binaries, their shared
#                                              #   libraries but the C runtime, the Vulkan loader,
#                                              #   libglvnd's packages)
#   bash scripts/device-check.sh run [DEVICE]  # on the device machine, in the repository root
#                                              #   with device-check/ carried along: bench_shading
#                                              #   at 3840x2160 at 1, 4 and 16 lights and its
#                                              #   table, then every suite with
#                                              #   SAAGEN_VK_DEVICE=DEVICE (default NVIDIA)
#   bash scripts/device-check.sh all [DEVICE]  # both, where one machine has the toolchain and the GPU
# BUILD_DIR=DIR builds in DIR instead of build-device (an existing Release build: only what is missing).
#
# The device machines here have no Debian packages (glslang, gtest, tinygltf...), so the build
# happens on the Debian machine and travels (device-check/ is ignored by git, .gitignore; name it
# in the device tool's `carry`). The test binaries hold this checkout's and build folder's absolute paths (SAAGEN_SOURCE_DIR, SAAGEN_CLI_PATH); `run` recreates them as links
# when the device machine's copy lies elsewhere. No validation layer is assumed there
# (SAAGEN_VK_VALIDATION is left unset); lavapipe and SwiftShader run the suites with it in ctest.
#
# Output (OUT=DIR, default device-check/out): the 4K table first, on an idle GPU: bench_shading at
# 3840x2160 at each light count of LIGHTS ("COUNT:ROUNDS ...", default "1:31 4:15 16:7"; the ratios
# are to no SAA with as many lights), each cut at BENCH_TIMEOUT seconds (default 100), in
# shading_4k_<COUNT>l.json and one table shading_4k.md. Then the suites, all at once (SUITE_JOBS,
# default all ten: the lent machine has 16 cores and one GPU they share), each cut at SUITE_TIMEOUT
# seconds (default 240): one log per suite and summary.txt (per suite: passed, failed, skipped,
# and every skip with its reason; the failures' first lines). The whole `run` ends within 9 minutes
# plus the unpacking (seconds), whatever the device's speed; a cut suite or bench is reported as such.
# Exit status: non-zero when a suite or a bench failed or was cut.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
stage=$root/device-check
build_dir=${BUILD_DIR:-$root/build-device}
all_suites=(test_harness_vulkan test_gpu_core test_gpu_fragment test_stability_sweep test_stability_properties_gpu test_spirv_library
            test_deferred_pass test_glints_gpu test_precision test_engines_gpu)
# SUITES="a b" runs some of them (run only), SUITES=none none; SHADING_4K=0 leaves the 4K bench out.
read -r -a suites <<< "${SUITES:-${all_suites[*]}}"
[[ ${suites[*]:-} == none ]] && suites=()

benches=(bench_shading bench_deferred_pass bench_glints)

build() {
  local log
  log=$(mktemp)
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSAAGEN_BUILD_TESTS=ON -DSAAGEN_BUILD_BENCH=ON \
    -DSAAGEN_BUILD_HARNESS=ON "${CMAKE_ARGS[@]}" > "$log" 2>&1 || { cat "$log"; rm -f "$log"; exit 1; }
  rm -f "$log"
  cmake --build "$build_dir" -j "$(nproc)" --target "${all_suites[@]}" "${benches[@]}" saagen_cli
  rm -rf "$stage"
  mkdir -p "$stage/tree/tests" "$stage/tree/bench" "$stage/tree/cli" "$stage/lib"
  local binaries=()
  for suite in "${all_suites[@]}"; do cp "$build_dir/tests/$suite" "$stage/tree/tests/"; binaries+=("$build_dir/tests/$suite"); done
  for bench in "${benches[@]}"; do cp "$build_dir/bench/$bench" "$stage/tree/bench/"; binaries+=("$build_dir/bench/$bench"); done
  cp "$build_dir/cli/saagen" "$stage/tree/cli/"
  binaries+=("$build_dir/cli/saagen")
  strip --strip-unneeded "$stage"/tree/*/* 2> /dev/null || true
  # Every shared library the binaries load, but the C and C++ runtime (the device machine's are
  # newer than bookworm's and stay compatible; carrying them would shadow its own).
  ldd "${binaries[@]}" | awk '/=> \//{print $3}' | sort -u | while read -r library; do
    case "$(basename "$library")" in
      libc.so.*|libm.so.*|libdl.so.*|librt.so.*|libpthread.so.*|ld-linux*|libstdc++.so.*|libgcc_s.so.*) ;;
      *) cp -L "$library" "$stage/lib/" ;;
    esac
  done
  download_glvnd "$stage/gl"
  printf 'source_dir=%s\nbuild_dir=%s\n' "$root" "$build_dir" > "$stage/paths"
  (cd "$stage" && XZ_OPT=-6 tar -cJf bundle.tar.xz tree lib gl && rm -rf tree lib gl)
  echo "device-check: staged $(du -h "$stage/bundle.tar.xz" | cut -f1) in device-check/ (carry it: the device tool's carry=[\"device-check\"])"
}

# The NVIDIA driver's Vulkan ICD (libGLX_nvidia) needs libglvnd's dispatch libraries, which the
# device machine's image lacks: without them the loader answers VK_ERROR_INCOMPATIBLE_DRIVER
# (seen on the lent H200). Debian's packages travel as .deb files (the device tool's notes).
glvnd_packages=(libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
download_glvnd() {
  local log
  log=$(mktemp)
  mkdir -p "$1"
  (cd "$1" && apt-get -q download "${glvnd_packages[@]}" > "$log" 2>&1) || { cat "$log"; rm -f "$log"; exit 1; }
  rm -f "$log"
}

# Unpack them into / where the dispatch library is missing (root only, as on the device machine).
install_glvnd() {
  local deb
  ldconfig -p 2> /dev/null | grep -q libGLdispatch && return 0
  [[ $(id -u) == 0 ]] || { echo "device-check: libGLdispatch is missing and only root may unpack libglvnd; the NVIDIA ICD may not load"; return 0; }
  for deb in "$1"/*.deb; do dpkg -x "$deb" /; done
  ldconfig
}

# Summary of each suite from its log (gtest's own lines): counts, every skip with its message
# ("FILE:LINE: Skipped" then the message), each failure's first message lines.
summarise() {
  python3 - "$@" << 'EOF'
import re, sys
for path in sys.argv[1:]:
    suite = path.rsplit("/", 1)[-1].removesuffix(".log")
    try:
        lines = open(path, errors="replace").read().splitlines()
    except OSError:
        print(f"{suite}: no log")
        continue
    passed, failed, skipped, block, current = 0, [], [], [], None
    for line in lines:
        if m := re.match(r"\[ RUN      \] (\S+)", line):
            current, block = m.group(1), []
        elif re.match(r"\[       OK \] (\S+)", line):
            passed += 1
        elif m := re.match(r"\[  SKIPPED \] (\S+) \(", line):
            text = [l for l in block if l.strip() and not re.search(r":\d+: Skipped$", l)]
            skipped.append((m.group(1), text[-1] if text else ""))
        elif m := re.match(r"\[  FAILED  \] (\S+) \(", line):
            marks = [i for i, l in enumerate(block) if re.search(r":\d+: Failure$", l)]
            failed.append((m.group(1), " ".join(block[marks[0] + 1:marks[0] + 3]) if marks else ""))
        elif current:
            block.append(line)
    finished = any(l.startswith("[==========]") and "ran." in l for l in lines)
    print(f"{suite}: {passed} passed, {len(failed)} failed, {len(skipped)} skipped" + ("" if finished else " (did not finish: crashed or cut)"))
    for name, reason in skipped:
        print(f"  skipped {name}: {reason}")
    for name, reason in failed:
        print(f"  FAILED  {name}: {reason[:300]}")
EOF
}

# bench_shading at 3840x2160 at each light count of LIGHTS, then one table of them all
# (docs/GPU_TIMINGS.md).
bench_4k() {
  local device=$1 built=$2 out=$3 status=0 tables=() entry
  for entry in ${LIGHTS:-1:31 4:15 16:7}; do
    local lights=${entry%%:*} rounds=${entry##*:}
    local json="$out/shading_4k_${lights}l.json"
    if timeout "${BENCH_TIMEOUT:-100}" "$built/bench/bench_shading" --device "$device" --size 3840x2160 --lights "$lights" \
         --repetitions "$rounds" --json "$json" > "$out/bench_shading_${lights}l.log" 2>&1; then
      tables+=("$json")
    else
      echo "device-check: bench_shading at 4K with $lights lights failed or was cut (see $out/bench_shading_${lights}l.log)"
      status=1
    fi
  done
  if (( ${#tables[@]} )); then python3 scripts/shading_cost_table.py "${tables[@]}" | tee "$out/shading_4k.md"; fi
  return "$status"
}

# Every suite at once, each cut at SUITE_TIMEOUT seconds, and the summary of their logs.
run_suites() {
  local built=$1 out=$2 start=$3 status=0 suite logs=()
  printf '%s\n' "${suites[@]}" | xargs -P "${SUITE_JOBS:-${#suites[@]}}" -I{} sh -c \
    'timeout "${SUITE_TIMEOUT:-240}" "$0/tests/{}" > "$1/{}.log" 2>&1; echo "{}: exit $? after $(( $(date +%s) - $2 )) s"' \
    "$built" "$out" "$start" | tee "$out/exits.txt"
  grep -qv ': exit 0 ' "$out/exits.txt" && status=1
  for suite in "${suites[@]}"; do logs+=("$out/$suite.log"); done
  summarise "${logs[@]}" | tee "$out/summary.txt"
  return "$status"
}

run() {
  local device=${1:-NVIDIA}
  local out=${OUT:-$stage/out}
  [[ -f $stage/bundle.tar.xz ]] || { echo "device-check: no device-check/bundle.tar.xz; run 'bash scripts/device-check.sh build' first"; exit 2; }
  local start
  start=$(date +%s)
  mkdir -p "$out"
  local unpacked=$stage/unpacked
  rm -rf "$unpacked"
  mkdir -p "$unpacked"
  tar -xJf "$stage/bundle.tar.xz" -C "$unpacked"
  # The absolute paths the binaries were built with.
  local source_dir built
  source_dir=$(sed -n 's/^source_dir=//p' "$stage/paths")
  built=$(sed -n 's/^build_dir=//p' "$stage/paths")
  if [[ ! -e $source_dir ]]; then mkdir -p "$(dirname "$source_dir")" && ln -s "$root" "$source_dir"; fi
  if [[ ! -e $built/tests/${all_suites[0]} ]]; then
    if [[ -L $built || ! -e $built ]]; then ln -sfn "$unpacked/tree" "$built"; else
      for folder in tests bench cli; do mkdir -p "$built/$folder" && cp -f "$unpacked/tree/$folder"/* "$built/$folder/"; done
    fi
  fi
  export LD_LIBRARY_PATH="$unpacked/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  [[ -d $unpacked/gl ]] && install_glvnd "$unpacked/gl"
  # The NVIDIA ICD where the loader does not find one by itself (the device tool's notes).
  if [[ -z ${VK_DRIVER_FILES:-}${VK_ICD_FILENAMES:-} && -f /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ]] &&
     ! ls /usr/share/vulkan/icd.d/*.json /etc/vulkan/icd.d/*.json > /dev/null 2>&1; then
    export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  fi
  export SAAGEN_VK_DEVICE=$device
  unset SAAGEN_VK_VALIDATION
  local status=0
  [[ ${SHADING_4K:-1} == 0 ]] || bench_4k "$device" "$built" "$out" || status=1
  if (( ${#suites[@]} )); then run_suites "$built" "$out" "$start" || status=1; fi
  echo "device-check: done in $(( $(date +%s) - start )) s on $device; results in $out"
  return "$status"
}

CMAKE_ARGS=()
command=${1:-all}
shift || true
case "$command" in
  build) build ;;
  run) run "$@" ;;
  all) build && run "$@" ;;
  *) echo "usage: bash scripts/device-check.sh build | run [DEVICE] | all [DEVICE]"; exit 2 ;;
esac
