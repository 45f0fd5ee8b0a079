#!/usr/bin/env python3
"""Writes generator/data/advice.json, the measurement the table-free advice is decided on, from two
`saagen bench --json` tables: the one it is derived from and the held-out one it is reported on;
and, under TAA, two more of the same scenes measured with --taa (their "taa_by_content" rows,
each configuration against none+taa).

    saagen bench --preset medium --json T.json
    bash scripts/held_out.sh OUT          # writes OUT/held_out.json
    saagen bench --preset medium --taa --sigma2 0.0625 --json TAA.json
    bash scripts/held_out.sh TAA_OUT --taa --sigma2 0.0625
    python3 scripts/advice_data.py T.json OUT/held_out.json TAA.json TAA_OUT/held_out.json > generator/data/advice.json

and, for normal maps seen only from afar (a manifest's `map_lod`), pairs of tables of the minification
sweep's scenes at that LOD (the derivation maps', the held-out maps'), each entered with
--map-lod K DERIVED HELD_OUT before the positional tables:

    saagen bench --preset medium --scene pmndrs-0014-lod4 --scene pmndrs-0019-lod4 --scene pmndrs-0010-lod4 --json D4.json
    saagen bench --preset medium --scene pmndrs-0000-lod4 --scene pmndrs-0001-lod4 --scene pmndrs-0002-lod4 --json H4.json
    python3 scripts/advice_data.py --map-lod 4 D4.json H4.json T.json OUT/held_out.json ... > generator/data/advice.json

It copies figures; it decides nothing. The planner (saagen/scene/cost_tables.hpp: committed_advice) reads the file,
embedded in the library (saagen/scene/cost_tables.hpp: committed_advice), and makes saagen's one decision (saagen/decision.hpp) on its rows: on the
derivation rows' comparisons with no SAA, then held against the held-out rows' comparisons.
"""
import json
import sys

# The bench's by_content figures the advice keeps per configuration.
FIGURES = ("image_error", "flicker_error", "video_error")


def scenes_by_content(table):
    """Each content type's scenes, in the table's order (from its per-scene decisions)."""
    scenes = {}
    for entry in table["decisions"]["per_scene"]:
        names = scenes.setdefault(entry["content"], [])
        if entry["scene"] not in names:
            names.append(entry["scene"])
    return scenes


def rows_by_content(table, key="by_content"):
    rows = {}
    for row in table.get(key, []):
        rows.setdefault(row["content"], {})[row["configuration"]] = row
    return rows


def content_entries(derived, held_out, key, taa, map_lod_min=0):
    """Per content type, every configuration's figures and comparisons: without TAA (by_content,
    against no SAA) or under TAA (taa_by_content, against none+taa); map_lod_min > 0: tables of
    scenes whose normal maps are all seen at that LOD or coarser."""
    if derived.get("alphas") != held_out.get("alphas"):
        sys.exit(f"advice_data.py: the derivation and held-out tables were measured at other alphas ({derived.get('alphas')} and "
                 f"{held_out.get('alphas')}); measure both with the same preset")
    derived_rows, held_rows = rows_by_content(derived, key), rows_by_content(held_out, key)
    derived_scenes, held_scenes = scenes_by_content(derived), scenes_by_content(held_out)
    contents = []
    for content, rows in derived_rows.items():
        held = held_rows.get(content, {})
        entry = {"content": content}
        if taa:
            entry.update({"taa": True, "baseline": "none+taa"})
        if map_lod_min:
            entry["map_lod_min"] = map_lod_min
        entry.update({"scenes": derived_scenes.get(content, []), "held_out_scenes": held_scenes.get(content, [])})
        if derived.get("alphas"):
            entry["alphas"] = derived["alphas"]
        entry["rows"] = []
        for configuration, row in rows.items():
            kept = {"configuration": configuration}
            kept.update({figure: row[figure] for figure in FIGURES if figure in row})
            if "against_none" in row:
                kept["against_none"] = row["against_none"]
            for pairing in ("loses_on", "not_worse_than", "loses_at"):
                if row.get(pairing):
                    kept[pairing] = row[pairing]
            if "against_none" in held.get(configuration, {}):
                kept["held_out"] = held[configuration]["against_none"]
            for pairing in ("loses_on", "loses_at"):
                if held.get(configuration, {}).get(pairing):
                    kept["held_out_" + pairing] = held[configuration][pairing]
            entry["rows"].append(kept)
        contents.append(entry)
    return contents


def half_vector_frame(tables):
    """The frame every table's projected forward filters were measured in (their "half_vector_frame";
    tables written before it had the key are "tangent"): the wrappers the planner then calls."""
    frames = {table.get("half_vector_frame", "tangent") for table in tables}
    if len(frames) != 1:
        sys.exit(f"advice_data.py: the tables were measured with other --half-vector-frame options ({', '.join(sorted(frames))}); "
                 "measure them all with the same one")
    return frames.pop()


def advice_document(derived, held_out, derived_name, held_out_name, taa_derived=None, taa_held_out=None, by_map_lod=()):
    """by_map_lod: (K, derived, held_out, derived_name, held_out_name) per map distance measured."""
    tables = [derived, held_out] + [t for t in (taa_derived, taa_held_out) if t is not None]
    tables += [t for _, d, h, _, _ in by_map_lod for t in (d, h)]
    contents = content_entries(derived, held_out, "by_content", False)
    for map_lod_min, lod_derived, lod_held_out, _, _ in by_map_lod:
        contents += content_entries(lod_derived, lod_held_out, "by_content", False, map_lod_min)
    taa = {}
    if taa_derived is not None:
        contents += content_entries(taa_derived, taa_held_out, "taa_by_content", True)
        taa = {"taa": {"table": "saagen bench --preset medium --taa --sigma2 0.0625 --json TAA.json",
                       "held_out_command": "bash scripts/held_out.sh OUT --taa --sigma2 0.0625",
                       "config": taa_derived["config"]}}
    return {
        "schema": "saagen advice 1",
        "about": "the table-free advice's measurement: per content type, every configuration's figures and its paired "
                 "comparison with no SAA (95 % intervals) on the scenes the advice is derived from, and on held-out scenes "
                 "it is only reported on; written by scripts/advice_data.py, read by the planner (saagen/scene/cost_tables.hpp: committed_advice)",
        "derived_from": {"table": derived_name, "config": derived["config"]},
        "forward_half_vector_frame": half_vector_frame(tables),
        "held_out": {"table": held_out_name, "command": "bash scripts/held_out.sh OUT", "config": held_out["config"]},
        "image_metric": "image error: LDR-FLIP of every animation frame against the ground truth's",
        "temporal_metric": "video error: 10 - the ColorVideoVDP JOD of the animation clip against the ground truth's (docs/TEMPORAL.md)",
        **taa,
        **({"map_lod": [{"map_lod_min": k, "table": d_name, "held_out": h_name, "config": d["config"]}
                        for k, d, _, d_name, h_name in by_map_lod]} if by_map_lod else {}),
        "content": contents,
    }


def rounded(value):
    """Figures to 6 significant digits: far below any interval, and a file a diff can read."""
    if isinstance(value, float):
        return float(f"{value:.6g}")
    if isinstance(value, dict):
        return {key: rounded(item) for key, item in value.items()}
    if isinstance(value, list):
        return [rounded(item) for item in value]
    return value


def write(document, out):
    """One configuration's row per line."""
    compact = lambda value: json.dumps(rounded(value), separators=(",", ":"))
    out.write("{\n")
    keys = [key for key in document if key != "content"]
    for key in keys:
        out.write(f' {json.dumps(key)}: {compact(document[key])},\n')
    out.write(' "content": [\n')
    for i, entry in enumerate(document["content"]):
        head = {key: value for key, value in entry.items() if key != "rows"}
        out.write("  " + compact(head)[:-1] + ',"rows": [\n')
        out.write(",\n".join("   " + compact(row) for row in entry["rows"]))
        out.write("\n  ]}" + ("," if i + 1 < len(document["content"]) else "") + "\n")
    out.write(" ]\n}\n")


def load(path):
    with open(path) as f:
        return json.load(f)


def sweep_command(table):
    """The bench command of a table of sweep scenes, from its scene names."""
    scenes = []
    for entry in table["decisions"]["per_scene"]:
        if entry["scene"] not in scenes:
            scenes.append(entry["scene"])
    return "saagen bench --preset medium " + " ".join(f"--scene {scene}" for scene in scenes)


def main(argv):
    usage = ("usage: advice_data.py [--map-lod K DERIVED.json HELD_OUT.json ...] DERIVED.json HELD_OUT.json "
             "[TAA_DERIVED.json TAA_HELD_OUT.json] > generator/data/advice.json")
    args, by_map_lod = argv[1:], []
    while args and args[0] == "--map-lod":
        if len(args) < 4 or not args[1].isdigit() or int(args[1]) < 1:
            sys.exit(usage)
        derived, held_out = load(args[2]), load(args[3])
        by_map_lod.append((int(args[1]), derived, held_out, sweep_command(derived), sweep_command(held_out)))
        args = args[4:]
    if len(args) not in (2, 4):
        sys.exit(usage)
    tables = [load(path) for path in args]
    document = advice_document(tables[0], tables[1], "saagen bench --preset medium --json T.json", "scripts/held_out.sh", *tables[2:],
                               by_map_lod=by_map_lod)
    write(document, sys.stdout)


if __name__ == "__main__":
    main(sys.argv)
