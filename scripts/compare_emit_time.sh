#!/usr/bin/env bash
# Compares the whole-process emission time of two saagen binaries in one run: every variant for
# every target and precision (glsl and gles fp32/fp16, hlsl fp32/min16, spirv), the two binaries
# interleaved ROUNDS times; prints each one's median CPU seconds (user + system, which a shared
# machine's load disturbs less than wall time) and the ratio AFTER / BEFORE. With
# --instructions, counts instead the instructions the seven processes execute under valgrind
# (lackey), which no load disturbs (one round: the count is deterministic).
#
# Usage: scripts/compare_emit_time.sh [--instructions] BEFORE_BINARY AFTER_BINARY [ROUNDS]
set -euo pipefail

count_instructions=false
if [[ ${1:-} == --instructions ]]; then
  count_instructions=true
  shift
fi

if [[ $# -lt 2 ]]; then
  echo "usage: $0 BEFORE_BINARY AFTER_BINARY [ROUNDS]" >&2
  exit 2
fi
before=$(realpath "$1")
after=$(realpath "$2")
rounds=${3:-7}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

emit_everything() {  # binary output_directory
  rm -rf "$2"
  "$1" emit --target glsl -o "$2/glsl" > /dev/null
  "$1" emit --target glsl --precision fp16 -o "$2/glsl16" > /dev/null
  "$1" emit --target gles -o "$2/gles" > /dev/null
  "$1" emit --target gles --precision fp16 -o "$2/gles16" > /dev/null
  "$1" emit --target hlsl -o "$2/hlsl" > /dev/null
  "$1" emit --target hlsl --precision min16 -o "$2/hlsl16" > /dev/null
  "$1" emit --target spirv -o "$2/spirv" > /dev/null
}

seconds() {  # binary output_directory: CPU seconds of the seven processes
  local TIMEFORMAT='%U %S' times
  times=$({ time emit_everything "$1" "$2"; } 2>&1)
  echo "$times" | awk '{ print $1 + $2 }'
}

instructions() {  # binary output_directory: instructions of the seven processes
  local total=0 count
  for arguments in "glsl" "glsl --precision fp16" "gles" "gles --precision fp16" "hlsl" "hlsl --precision min16" "spirv"; do
    # shellcheck disable=SC2086
    count=$(valgrind --tool=lackey --basic-counts=yes "$1" emit --target $arguments -o "$2/$RANDOM" 2>&1 >/dev/null |
            sed -n 's/.*guest instrs: *\([0-9,]*\).*/\1/p' | tr -d ,)
    total=$((total + count))
  done
  echo "$total"
}

if $count_instructions; then
  before_count=$(instructions "$before" "$work")
  after_count=$(instructions "$after" "$work")
  echo "before: $before_count instructions ($before)"
  echo "after:  $after_count instructions ($after)"
  printf 'ratio after/before: %.4f\n' "$(echo "$after_count / $before_count" | bc -l)"
  exit 0
fi

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

: > "$work/before.txt"
: > "$work/after.txt"
for ((round = 0; round < rounds; ++round)); do
  seconds "$before" "$work/out" >> "$work/before.txt"
  seconds "$after" "$work/out" >> "$work/after.txt"
done
before_median=$(median < "$work/before.txt")
after_median=$(median < "$work/after.txt")
printf 'before: median %.3f CPU s over %d rounds (%s)\n' "$before_median" "$rounds" "$before"
printf 'after:  median %.3f CPU s over %d rounds (%s)\n' "$after_median" "$rounds" "$after"
printf 'ratio after/before: %.3f\n' "$(echo "$after_median / $before_median" | bc -l)"
