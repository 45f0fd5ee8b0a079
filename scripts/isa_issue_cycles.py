#!/usr/bin/env python3
"""ACO's inverse-throughput ratios next to the same shaders' issue cycles counted once per instruction.

`saagen bench --isa` costs a configuration by ACO's inverse-throughput estimate (Mesa,
src/amd/compiler/aco_statistics.cpp, collect_preasm_stats). That estimate weights each block by the
trip counts it assumes: 0.75 per level of divergent `if` and 0.5 per uniform one (a loop 8 times).
A BRDF's early returns (below the horizon, a back-facing half vector) put the lobe's arithmetic one
to three divergent levels deep, where it counts 0.75, 0.56 or 0.42 of its cost, while the code
before them (the scene, a deferred form's G-buffer side) counts in full. Where every lane of a wave
passes those tests, as on a lit highlight, the GPU issues every instruction once.

This script reruns `saagen bench --isa FAMILY --isa-only` with RADV's shader dump
(RADV_DEBUG=shaders,nocache), reads each forward-shading fragment shader's disassembly and counts
its issue cycles on GFX9 as ACO's own table for GFX6-9 does (4 per VALU instruction, 16 per
transcendental: rcp, rsq, sqrt, exp, log, sin, cos), every block once. It prints, per target and
light count, both ratios to no SAA with as many lights.

usage: isa_issue_cycles.py SAAGEN [--lights 1] [--target glsl]
       isa_issue_cycles.py --self-test
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

FAMILY = "vega10"  # GFX9: the issue costs below are its (GFX10+ issue wave32 VALU in one cycle)
TRANSCENDENTAL = re.compile(r"v_(rcp|rsq|sqrt|exp|log|sin|cos)_f(16|32)(_e(32|64))?\s")
STAGE = re.compile(r"ACO shader stage: (\w+)")
VALU_CYCLES, TRANSCENDENTAL_CYCLES = 4, 16
# ACO's instruction statistic counts its IR before the last passes; the disassembly of the same
# shader differs from it by a few instructions (s_code_end padding, wait states): 8, or 1 % of a
# long shader.
INSTRUCTION_SLACK, INSTRUCTION_SLACK_SHARE = 8, 0.01


def fragment_disassemblies(dump):
    """The disassembly of every fragment shader in a RADV_DEBUG=shaders dump, in compile order."""
    marks = list(STAGE.finditer(dump))
    shaders = []
    for mark, following in zip(marks, marks[1:] + [None]):
        if mark.group(1) != "fragment_fs":
            continue
        body = dump[mark.end():following.start() if following else len(dump)]
        at = body.find("disasm:")
        if at < 0:
            raise SystemExit("isa_issue_cycles.py: a fragment shader in the dump has no disassembly (RADV_DEBUG=shaders)")
        shaders.append(body[at + len("disasm:"):])
    return shaders


def issue_cycles(disassembly):
    """(instructions, VALU issue cycles) of one shader's disassembly, every instruction once."""
    instructions = cycles = last = 0
    for line in disassembly.splitlines():
        text = line.strip()
        # The disassembler folds a run of one instruction into "(then repeated N times)".
        repeated = re.match(r"\(then repeated (\d+) times?\)", text)
        if repeated:
            instructions += int(repeated.group(1))
            cycles += int(repeated.group(1)) * last
            continue
        if not re.match(r"[vs]_\w", text):
            continue
        instructions += 1
        last = 0
        if text.startswith("v_"):
            last = TRANSCENDENTAL_CYCLES if TRANSCENDENTAL.match(text) else VALU_CYCLES
        cycles += last
    return instructions, cycles


def measured(saagen):
    """The bench's forward rows on FAMILY, in measurement order, and the fragment dumps."""
    with tempfile.TemporaryDirectory() as folder:
        table = os.path.join(folder, "isa.json")
        environment = dict(os.environ, RADV_DEBUG="shaders,nocache")
        run = subprocess.run([saagen, "bench", "--isa", FAMILY, "--isa-only", "--isa-table", table],
                             env=environment, capture_output=True, text=True)
        if run.returncode != 0:
            last = (run.stderr.strip().splitlines() or ["no message"])[-1]
            raise SystemExit(f"isa_issue_cycles.py: {saagen} bench --isa {FAMILY} failed: {last}")
        with open(table) as handle:
            rows = [row for row in json.load(handle)["rows"] if row["device"] == FAMILY and row["shader"] == "forward"]
    return rows, fragment_disassemblies(run.stderr)


def paired(rows, shaders):
    """Each row with its shader's issue cycles; the instruction counts prove the pairing."""
    if len(rows) != len(shaders):
        raise SystemExit(f"isa_issue_cycles.py: {len(rows)} forward rows but {len(shaders)} fragment shaders in the dump")
    result = []
    for row, shader in zip(rows, shaders):
        instructions, cycles = issue_cycles(shader)
        if abs(instructions - row["instructions"]) > max(INSTRUCTION_SLACK, INSTRUCTION_SLACK_SHARE * row["instructions"]):
            raise SystemExit(f"isa_issue_cycles.py: {row['variant']} ({row['target']}, {row['lights']} lights) has "
                             f"{row['instructions']:.0f} instructions in the table but {instructions} in its dump")
        result.append(dict(row, issue_cycles=cycles))
    return result


def ratios(rows):
    """(variant, ACO's ratio, the issue cycles' ratio) per row of one target and light count."""
    baseline = next(row for row in rows if row["variant"] == "no-saa")
    return [(row["variant"], row["inverse_throughput"] / baseline["inverse_throughput"],
             row["issue_cycles"] / baseline["issue_cycles"]) for row in rows]


def print_table(rows, target, lights):
    chosen = [row for row in rows if row["target"] == target and row["lights"] == lights]
    if not chosen:
        raise SystemExit(f"isa_issue_cycles.py: no rows for {target} at {lights} light(s)")
    print(f"{FAMILY}, {target}, {lights} light(s): ratio to no SAA by ACO's inverse throughput and by issue cycles "
          "(every instruction once)")
    print(f"{'configuration':42} {'ACO':>7} {'issue':>7}")
    for variant, aco, issue in ratios(chosen):
        print(f"{variant:42} {aco:7.3f} {issue:7.3f}")


SAMPLE = """ACO shader stage: vertex_vs
disasm:
\tv_mov_b32_e32 v0, 0
ACO shader stage: fragment_fs
\t v1: %1:v[0] = v_rcp_f32 %0:v[0]
disasm:
\ts_mov_b64 s[0:1], exec ; be80017e
\tv_rcp_f32_e32 v1, v0 ; 7e024500
\tv_mul_f32_e32 v1, v1, v1 ; 0a020301
\ts_endpgm ; bf810000
ACO shader stage: fragment_fs
disasm:
\ts_nop 0 ; bf800000
(then repeated 2 times)
\tv_rsq_f32_e32 v1, v0 ; 7e024900
\tv_sqrt_f32_e32 v1, v1 ; 7e024f01
\tv_mad_f32 v1, v1, v1, 1.0 ; d1c10001
\tv_mul_f32_e32 v1, v1, v1 ; 0a020301
\ts_endpgm ; bf810000
ACO shader stage: compute_cs
disasm:
\tv_exp_f32_e32 v1, v0 ; 7e024100
"""


def self_test():
    shaders = fragment_disassemblies(SAMPLE)
    assert len(shaders) == 2, shaders
    # The vertex and compute shaders are not counted, nor the IR above "disasm:".
    assert issue_cycles(shaders[0]) == (4, 16 + 4), issue_cycles(shaders[0])
    assert issue_cycles(shaders[1]) == (8, 16 + 16 + 4 + 4), issue_cycles(shaders[1])
    rows = [{"variant": "no-saa", "target": "glsl", "lights": 1, "instructions": 4, "inverse_throughput": 10},
            {"variant": "x", "target": "glsl", "lights": 1, "instructions": 8, "inverse_throughput": 12}]
    both = paired(rows, shaders)
    assert ratios(both) == [("no-saa", 1.0, 1.0), ("x", 1.2, 40 / 20)], ratios(both)
    try:
        paired([dict(rows[0], instructions=40), rows[1]], shaders)
    except SystemExit as error:
        assert "40 instructions in the table but 4 in its dump" in str(error), error
    else:
        raise AssertionError("a mismatched pairing was accepted")
    print("isa_issue_cycles.py self-test: ok")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("saagen", nargs="?")
    parser.add_argument("--lights", type=int, default=1)
    parser.add_argument("--target", default="glsl")
    parser.add_argument("--self-test", action="store_true")
    arguments = parser.parse_args()
    if arguments.self_test:
        self_test()
        return
    if not arguments.saagen:
        parser.error("give the saagen binary (build/cli/saagen), or --self-test")
    rows, shaders = measured(arguments.saagen)
    print_table(paired(rows, shaders), arguments.target, arguments.lights)


if __name__ == "__main__":
    sys.exit(main())
