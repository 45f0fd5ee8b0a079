#!/usr/bin/env bash
# The held-out set: content the table-free advice (generator/data/advice.json) was NOT derived
# from, measured with the medium preset's settings, so that the advice is reported on it.
#   bash scripts/held_out.sh OUT [saagen bench options]   # e.g. --cache out/cache
# ($SAAGEN names the saagen binary; default ./build/cli/saagen.)
# Writes OUT/models/*.glb (converted here, nothing is committed), OUT/held_out.json (the trade
# table) and OUT/held_out.txt (the bench's output).
# The set, chosen by a rule and not by how the advice fares on it:
#   - curved: the three curved, smooth, textured models of Debian's assimp-testmodels with 3-4 k
#     triangles (Collada duck, OBJ Wuson, Collada teapots), converted to glTF by assimp-utils;
#   - normal-mapped: the first three normal maps of @pmndrs/assets (0000, 0001, 0002) on the
#     sphere, as the derivation set's maps (0010, 0014, 0019) are, and, as the medium preset
#     sweeps its maps' minification, each at LOD 0, 1, 3 and 4 (pmndrs-NNNN-lodK).
# Bumps and clearcoat have no held-out content (no package ships a second asset of either).
# The models' ground truths are at 4096 spp (the presets' rule for glTF scenes; saagen/report/presets.hpp).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: scripts/held_out.sh OUT [saagen bench options]}
shift
command -v assimp > /dev/null || { echo "held_out.sh: assimp is needed (scripts/install-deps.sh installs assimp-utils)"; exit 1; }
models=/usr/share/assimp/models
mkdir -p "$out/models"
scenes=()
for source in Collada/duck.dae OBJ/WusonOBJ.obj Collada/teapots.DAE; do
  name=$(basename "${source%.*}")
  assimp export "$models/$source" "$out/models/$name.glb" -fglb2 > "$out/models/$name.log" 2>&1 ||
    { cat "$out/models/$name.log"; echo "held_out.sh: assimp could not convert $models/$source"; exit 1; }
  scenes+=(--scene "$out/models/$name.glb")
done
for map in 0000 0001 0002; do scenes+=(--scene "pmndrs-$map"); done
for map in 0000 0001 0002; do for lod in 0 1 3 4; do scenes+=(--scene "pmndrs-$map-lod$lod"); done; done
"${SAAGEN:-./build/cli/saagen}" bench --preset medium "${scenes[@]}" --json "$out/held_out.json" "$@" | tee "$out/held_out.txt"
