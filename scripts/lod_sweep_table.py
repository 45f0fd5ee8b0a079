#!/usr/bin/env python3
"""The normal-map minification sweep of a `saagen bench --json` table, by LOD: per configuration and
LOD, on how many of the maps it beats / ties / is mixed / loses against no SAA (the bench's own
per-scene comparisons, 95 % intervals), and its mean image and video error differences over them.
The scenes are the pmndrs-NNNN-lodK ones (measure/assets.hpp: implicit LOD K + 0.22 at the centre of
the medium preset's 64 px images); a plain pmndrs-NNNN scene counts as LOD 2. It reads what the
bench compared; it decides nothing.

    python3 scripts/lod_sweep_table.py T.json [--maps 0014,0019,0010] CONFIGURATION ...
"""
import json
import re
import sys

SCENE = re.compile(r"^pmndrs-(\d{4})(?:-lod(\d))?$")


def lod_of(scene):
    """(map, LOD) of a sweep scene, None for any other scene."""
    match = SCENE.match(scene)
    if not match:
        return None
    return match.group(1), int(match.group(2)) if match.group(2) else 2


def main(argv):
    args = argv[1:]
    if not args:
        sys.exit(__doc__)
    maps = None
    if "--maps" in args:
        at = args.index("--maps")
        maps = set(args[at + 1].split(","))
        del args[at:at + 2]
    path, configurations = args[0], args[1:]
    with open(path) as f:
        table = json.load(f)
    cells = {}  # (configuration, lod) -> [comparison]
    for c in table["comparisons"]:
        if c.get("scope") != "scene" or c.get("baseline") != "none":
            continue
        place = lod_of(c["name"])
        if not place or (maps and place[0] not in maps):
            continue
        cells.setdefault((c["configuration"], place[1]), []).append(c)
    lods = sorted({lod for (_, lod) in cells})
    print("| configuration | LOD | maps | beats / ties / mixed / loses | image error vs no SAA | video error vs no SAA |")
    print("|---|---:|---:|---|---:|---:|")
    for configuration in configurations:
        for lod in lods:
            found = cells.get((configuration, lod), [])
            if not found:
                continue
            counts = [sum(1 for c in found if c["outcome"] == o) for o in ("beats", "ties", "mixed", "loses")]
            image = sum(c["image_error"]["mean"] for c in found) / len(found)
            video = sum(c["video_error"]["mean"] for c in found) / len(found)
            print(f"| {configuration} | {lod} | {len(found)} | {' / '.join(map(str, counts))} | {image:+.4f} | {video:+.2f} |")


if __name__ == "__main__":
    main(sys.argv)
