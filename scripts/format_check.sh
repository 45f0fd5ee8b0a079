#!/usr/bin/env bash
# The formatting check (ctest `format_check`, so scripts/test.sh and CI run it): every C and C++
# file of the repository must be as `clang-format` with the root .clang-format writes it
# (`clang-format --dry-run -Werror`), the whole tree.
#
#   bash scripts/format_check.sh            # check; exit 1 naming each file that is not formatted
#   bash scripts/format_check.sh --fix      # format every checked file in place (clang-format -i)
#
# clang-format is Debian's (scripts/install-deps.sh installs it; bookworm: version 14). Files are
# git's tracked and not-ignored ones (a tree without git: every file outside build folders).
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v clang-format > /dev/null; then
  echo "format_check: clang-format is not installed (scripts/install-deps.sh installs it)"
  exit 1
fi

if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  mapfile -t all < <(git ls-files --cached --others --exclude-standard -- '*.cpp' '*.hpp' '*.h' '*.c' '*.cc' '*.inl' |
                     grep -v -E '^(build[^/]*|node_modules|out)/' | sort -u)
else
  mapfile -t all < <(find . -type d \( -name 'build*' -o -name node_modules -o -name out -o -name '.*' -a ! -name . \) -prune -o \
                       -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.c' -o -name '*.cc' -o -name '*.inl' \) -print |
                     sed 's|^\./||' | sort)
fi

checked=()
for file in "${all[@]}"; do
  [ -f "$file" ] && checked+=("$file")
done

if [ "${1:-}" = "--fix" ]; then
  printf '%s\0' "${checked[@]}" | xargs -0 clang-format -i
  echo "format_check: formatted ${#checked[@]} files"
  exit 0
fi

# One clang-format run per batch of files; its diagnostics name each file that differs.
report=$(printf '%s\0' "${checked[@]}" | xargs -0 clang-format --dry-run -Werror 2>&1 || true)
mapfile -t bad < <(printf '%s\n' "$report" | sed -n 's/^\(.*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' | sort -u)

version=$(clang-format --version | sed -n 's/.*version \([0-9][0-9.]*\).*/\1/p')
if [ ${#bad[@]} -gt 0 ]; then
  for file in "${bad[@]}"; do
    echo "format_check: $file is not formatted (clang-format -i $file; the first differences:)"
    printf '%s\n' "$report" | grep -F -A 2 -m 3 "$file:" | sed 's/^/    /'
  done
  echo "format_check: ${#bad[@]} of ${#checked[@]} files not formatted (clang-format $version)"
  exit 1
fi
if printf '%s\n' "$report" | grep -q 'error'; then
  printf '%s\n' "$report" | head -n 20
  echo "format_check: clang-format failed"
  exit 1
fi
echo "format_check: ${#checked[@]} files formatted (clang-format $version)"
