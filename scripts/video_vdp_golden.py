#!/usr/bin/env python3
"""The golden JODs of tests/measure/test_video_vdp.cpp: the reference implementation of ColorVideoVDP
(pycvvdp, from a checkout) on the test's synthetic clips (tests/support/video_vdp_clips.hpp), printed as
the test's C++ table.

    python3 scripts/video_vdp_golden.py --cvvdp /path/to/ColorVideoVDP [--tool build/bench/video_vdp_frames]

Writes the clips with `video_vdp_frames --write-synthetic DIR` (the C++ generator the test uses),
runs scripts/video_metric.py on them (display standard_fhd, 30 fps; the 32 x 32 x 16 group also at
60 fps, whose temporal filters have 17 taps) and prints one line per clip: { "group", "variant",
fps, jod }. JODs are video_metric.py's, rounded to 4 decimals. Needs the checkout and torch
(video_metric.py's requirements); the test itself needs neither.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cvvdp", required=True, help="a ColorVideoVDP checkout (has pycvvdp/)")
    parser.add_argument("--tool", default=os.path.join(ROOT, "build", "bench", "video_vdp_frames"),
                        help="the C++ tool that writes the clips (default: build/bench/video_vdp_frames)")
    args = parser.parse_args()
    metric = os.path.join(ROOT, "scripts", "video_metric.py")
    with tempfile.TemporaryDirectory(prefix="video_vdp_golden.") as work:
        frames = os.path.join(work, "frames")
        subprocess.run([args.tool, "--write-synthetic", frames], check=True, stdout=sys.stderr)
        runs = [(30, None), (60, "^synthetic-s32/")]
        lines = []
        for fps, pattern in runs:
            out = os.path.join(work, f"R{fps}.json")
            command = [sys.executable, metric, "--cvvdp", args.cvvdp, "--frames", frames, "--fps", str(fps),
                       "--out", out]
            if pattern:
                command += ["--filter", pattern]
            subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
            with open(out) as f:
                result = json.load(f)
            if fps == runs[0][0]:
                print(f"// pycvvdp {result['cvvdp_version']} (commit {result['cvvdp_commit'][:12]}), torch "
                      f"{result['torch']}, display {result['display']}")
            for row in result["rows"]:
                group = row["scene"].removeprefix("synthetic-")
                lines.append(f'    {{"{group}", "{row["configuration"]}", {fps}, {row["jod"]:.4f}}},')
        print("\n".join(lines))


if __name__ == "__main__":
    main()
