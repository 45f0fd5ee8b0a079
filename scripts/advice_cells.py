#!/usr/bin/env python3
"""Prints, for each content decision of a `saagen bench --json` table, the (scene, alpha) cells
where the chosen configuration is worse than no SAA beyond both cells' 95 % intervals in the
image error or the video error (10 - ColorVideoVDP's JOD): what a content's pooled decision hides
cell by cell.

    python3 scripts/advice_cells.py T.json

A cell's intervals are each configuration's own (over frame blocks and the ground truth's seeds),
not a paired difference, so this is conservative: a cell listed is worse by more than either
interval allows. It reads the bench's decisions (`decisions.by_content`, `decisions.per_scene`) and
its cases; it decides nothing itself.
"""
import json
import sys


def worse_beyond(chosen, none, metric):
    """Whether the chosen configuration's interval lies wholly above no SAA's in `metric`."""
    return chosen[metric]["low"] > none[metric]["high"]


def cell_text(scene, alpha, chosen, none):
    parts = []
    for metric, label, digits in (("image_error", "image", 4), ("video_error", "video", 2)):
        difference = chosen[metric]["mean"] - none[metric]["mean"]
        mark = " (worse)" if worse_beyond(chosen, none, metric) else ""
        parts.append(f"{label} {difference:+.{digits}f}{mark}")
    return f"{scene} at alpha {alpha:g}: " + ", ".join(parts)


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: advice_cells.py T.json")
    with open(argv[1]) as f:
        table = json.load(f)
    decisions = table["decisions"]
    scenes_of = {}
    for entry in decisions["per_scene"]:
        scenes_of.setdefault(entry["content"], [])
        if entry["scene"] not in scenes_of[entry["content"]]:
            scenes_of[entry["content"]].append(entry["scene"])
    cases = {(c["scene"], c["alpha"], c["configuration"]): c for c in table["cases"] if not c.get("fresnel")}
    for entry in decisions["by_content"]:
        chosen = entry.get("chosen")
        if not chosen or chosen == "none":
            continue
        cells = []
        for scene in scenes_of.get(entry["content"], []):
            for alpha in sorted({a for (s, a, _) in cases if s == scene}):
                mine, none = cases.get((scene, alpha, chosen)), cases.get((scene, alpha, "none"))
                if mine and none and (worse_beyond(mine, none, "image_error") or worse_beyond(mine, none, "video_error")):
                    cells.append(cell_text(scene, alpha, mine, none))
        total = sum(len({a for (s, a, _) in cases if s == scene}) for scene in scenes_of.get(entry["content"], []))
        print(f'{entry["path"]}, {entry["content"]}: {chosen} is worse than no SAA in {len(cells)} of {total} cells')
        for cell in cells:
            print(f"    {cell}")


if __name__ == "__main__":
    main(sys.argv)
