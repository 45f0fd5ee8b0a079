#!/usr/bin/env python3
"""The shading cost of each variant against no SAA, and of each tail-lobe variant against the same
filter with the papers' lobe, from bench_shading's JSON (one file per size, light count or device):

    build/bench/bench_shading --device NAME --size 3840x2160 --repetitions 31 --json 4k.json
    python3 scripts/shading_cost_table.py 4k.json [1000.json ...]

A file measured with more than one light (--lights N) heads its columns "N lights".

Each ratio is the cost table's cost_ratio (bench_shading: the median over rounds of variant ms / no-SAA ms measured back to
back, so a change of clock between rounds cancels). "tail / papers" divides two such ratios.
"""
import json
import sys


def load(path):
    with open(path) as handle:
        document = json.load(handle)
    ratios = {(row["target"], row["variant"]): row["cost_ratio"] for row in document["rows"]}
    label = f'{document["width"]}x{document["height"]}'
    lights = document.get("lights", 1)
    if lights != 1:
        label += f" {lights} lights"
    return label, document["device"], ratios


def main(paths):
    tables = [load(path) for path in paths]
    print("device: " + "; ".join(sorted({device.split(" (")[0] for _, device, _ in tables})))
    header = " | ".join(f"{size} {target}" for size, _, _ in tables for target in ("glsl", "hlsl"))
    print(f"| variant | {header} |")
    print("|---|" + "---:|" * (2 * len(tables)))
    variants = [variant for (target, variant) in tables[0][2] if target == "glsl" and variant != "no-saa"]
    for variant in variants:
        cells = [f"{ratios[(target, variant)]:.3f}" for _, _, ratios in tables for target in ("glsl", "hlsl")]
        print(f"| {variant} | {' | '.join(cells)} |")
    for variant in variants:
        if not variant.endswith("/tail"):
            continue
        papers = variant[: -len("/tail")]
        if (tables[0][2]).get(("glsl", papers)) is None:
            continue  # no papers'-lobe row of this filter (deferred-aniso is saagen's)
        cells = [f"{ratios[(target, variant)] / ratios[(target, papers)]:.3f}" for _, _, ratios in tables for target in ("glsl", "hlsl")]
        print(f"| {variant} / {papers} | {' | '.join(cells)} |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: shading_cost_table.py BENCH_SHADING.json [MORE.json ...]")
    main(sys.argv[1:])
