#!/usr/bin/env bash
# The README's command-line example, run as it is written (ctest `readme_cli_example`): the ```sh
# block under "1. The command line" runs in a scratch folder where ./build/cli/saagen is SAAGEN and
# examples/ is the repository's, and must exit 0 having written what its comments name.
#   bash scripts/readme_example.sh [SAAGEN]   (default: build/cli/saagen)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
saagen=$(realpath "${1:-$root/build/cli/saagen}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
awk '/^\*\*1\. The command line/ { inside = 1 } inside && /^```sh/ { block = 1; next } block && /^```/ { exit } block' \
  "$root/README.md" > "$work/example.sh"
[ -s "$work/example.sh" ] || { echo "readme_example: no \`\`\`sh block under \"1. The command line\" in README.md"; exit 1; }
mkdir -p "$work/build/cli"
ln -s "$saagen" "$work/build/cli/saagen"
ln -s "$root/examples" "$work/examples"
(cd "$work" && bash -euo pipefail example.sh > log.txt 2>&1) || { cat "$work/log.txt"; echo "readme_example: the README's example failed"; exit 1; }
# Every output path its comments name (out/...) exists.
missing=0
for path in $(grep -o 'out/[A-Za-z0-9_./-]*\.[a-z]*' "$work/example.sh" | sort -u); do
  [ -e "$work/$path" ] || { echo "readme_example: $path, named in the example, was not written"; missing=1; }
done
[ "$missing" -eq 0 ] || exit 1
echo "readme_example: the README's command-line example ran ($(grep -c . "$work/example.sh") lines)"
