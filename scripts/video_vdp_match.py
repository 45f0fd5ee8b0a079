#!/usr/bin/env python3
"""How closely saagen's C++ ColorVideoVDP (measure/include/saagen/measure/video_vdp.hpp)
matches the reference implementation (pycvvdp) on the same clips: |JOD_cpp - JOD_py| over every
row (max, median, 95th percentile), the same on the sanity rows (`sanity:*`), and Kendall tau-b
between the two JODs per scene and alpha (docs/COLORVIDEOVDP.md).

    python3 scripts/video_vdp_match.py --python R.json --frames FRAMES [--cpp J.json]
        [--tool build/bench/video_vdp_frames] [--threads N]
    python3 scripts/video_vdp_match.py --python R.json --cpp J.json

R.json is what scripts/video_metric.py --out wrote for the clips of FRAMES (saagen bench --frames,
or bench/video_vdp_frames --write-synthetic); with --frames the C++ tool is run on the same rows
(R.json's filter and reference clip) and its rows go to --cpp (default: a temporary file); without
it --cpp is read. Needs neither the ColorVideoVDP checkout nor torch. Exit status 1 when a row of
R.json has no C++ JOD.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from video_metric import alpha_key, kendall_tau  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def key(row):
    return (row["scene"], alpha_key(row["alpha"]), bool(row.get("fresnel", False)), row["configuration"])


def percentile(values, p):
    """The p-th percentile by linear interpolation between the closest ranks (numpy's default)."""
    s = sorted(values)
    if not s:
        return float("nan")
    position = (len(s) - 1) * p / 100.0
    low = math.floor(position)
    high = min(low + 1, len(s) - 1)
    return s[low] + (s[high] - s[low]) * (position - low)


def summary(label, differences):
    if not differences:
        return f"{label}: no rows"
    worst = max(differences, key=lambda d: d[0])
    return (f"{label}: {len(differences)} rows, |dJOD| max {worst[0]:.5f} ({worst[1]}), "
            f"median {percentile([d[0] for d in differences], 50):.5f}, "
            f"p95 {percentile([d[0] for d in differences], 95):.5f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--python", required=True, help="scripts/video_metric.py --out of the clips (pycvvdp's JODs)")
    parser.add_argument("--cpp", help="bench/video_vdp_frames --out (written when --frames is given)")
    parser.add_argument("--frames", help="the clips' folder: run the C++ tool on it")
    parser.add_argument("--tool", default=os.path.join(ROOT, "build", "bench", "video_vdp_frames"),
                        help="the C++ tool (default: build/bench/video_vdp_frames)")
    parser.add_argument("--threads", type=int, default=0, help="the tool's threads (default: all cores)")
    args = parser.parse_args()

    with open(args.python) as f:
        python = json.load(f)
    if args.frames:
        cpp_path = args.cpp or os.path.join(tempfile.mkdtemp(prefix="video_vdp_match."), "J.json")
        command = [args.tool, "--frames", args.frames, "--out", cpp_path, "--fps", str(python.get("fps", 30)),
                   "--threads", str(args.threads)]
        if python.get("filter"):
            command += ["--filter", python["filter"]]
        if python.get("reference_clip", "ground-truth") != "ground-truth":
            command += ["--reference-clip", python["reference_clip"]]
        if python.get("display", "standard_fhd") != "standard_fhd":
            sys.exit(f"video_vdp_match: {args.python} is for display {python['display']}; the C++ tool runs standard_fhd")
        print(" ".join(command), file=sys.stderr)
        subprocess.run(command, check=True)
    elif not args.cpp:
        sys.exit("video_vdp_match: give --frames DIR (to run the C++ tool) or --cpp J.json")
    else:
        cpp_path = args.cpp
    with open(cpp_path) as f:
        cpp = {key(r): r for r in json.load(f)["rows"]}

    rows, missing = [], []
    for r in python["rows"]:
        c = cpp.get(key(r))
        if c is None:
            missing.append("/".join(map(str, key(r))))
            continue
        rows.append((key(r), float(r["jod"]), float(c["jod"]), c.get("seconds")))
    differences = [(abs(cj - pj), "/".join(map(str, k))) for k, pj, cj, _ in rows]
    print(f"ColorVideoVDP: C++ (saagen) against pycvvdp {python.get('cvvdp_version', '?')} "
          f"({python.get('cvvdp_commit', '?')[:12]}), display {python.get('display')}, {python.get('fps')} fps; "
          f"pycvvdp's JODs are rounded to 4 decimals")
    print(summary("all rows", differences))
    print(summary("sanity rows", [d for d, (k, *_rest) in zip(differences, rows) if k[3].startswith("sanity:")]))
    groups = {}
    for k, pj, cj, _ in rows:
        groups.setdefault(k[:3], []).append((pj, cj))
    # The rows tied in R.json's 4 decimals but not in the C++ JODs lower tau-b below 1; with the
    # C++ JODs rounded as R.json's, tau measures the order alone.
    for label, rounding in (("", None), (", C++ JOD rounded to 4 decimals as R.json's", 4)):
        taus = []
        for g, pairs in sorted(groups.items()):
            cpp_jods = [c if rounding is None else round(c, rounding) for _, c in pairs]
            tau = kendall_tau([p for p, _ in pairs], cpp_jods)
            if tau is not None:
                taus.append((tau, g, len(pairs)))
        if taus:
            worst = min(taus)
            print(f"Kendall tau-b (C++ JOD vs pycvvdp JOD{label}) per scene and alpha, {len(taus)} groups: min "
                  f"{worst[0]:+.4f} ({worst[1][0]} alpha {worst[1][1]}{' Fresnel' if worst[1][2] else ''}, "
                  f"n = {worst[2]}), {sum(t == 1.0 for t, _, _ in taus)} groups at 1")
    seconds = [s for *_x, s in rows if s is not None]
    if seconds:
        print(f"C++ time per comparison (one thread): mean {sum(seconds) / len(seconds):.4f} s")
    if missing:
        print(f"{len(missing)} rows of {args.python} have no C++ JOD, e.g. {missing[0]}")
        sys.exit(1)


if __name__ == "__main__":
    main()
