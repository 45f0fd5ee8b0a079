#!/usr/bin/env python3
"""The WebGPU and WebGL2 proofs as one table: per function and form, the worst error as a
fraction of its bound on each web backend, from the lines the suites print
("[ webgpu   ] <function> (<variant>, <form>): worst error / bound R (...); F of N outside",
tests/support/web_support.hpp's Worst::summary; "[ webgl2   ] highp|mediump <function> (...)").

    python3 scripts/web_table.py build/tests/test_wgsl build/tests/test_webgl
    python3 scripts/web_table.py build/tests/test_wgsl build/tests/test_webgl -- --gtest_filter='*Glint*'   # the glint rows

Each argument before `--` is a test executable (run, with the arguments after `--`) or a saved
log of one. Exit status 1 when a row is outside its bound or a run failed.
"""
import os
import re
import subprocess
import sys
from collections import OrderedDict

LINE = re.compile(r"^\[ (webgpu|webgl2) +\] (?:(highp|mediump) )?(\S+) \(([^,()]+), ([^()]+)\): worst error / bound (\S+) "
                  r"\(.*\); (\d+) of (\d+) outside$")


def output_of(path, extra):
    if os.access(path, os.X_OK) and not os.path.isdir(path):
        run = subprocess.run([path, *extra], capture_output=True, text=True)
        return run.stdout + run.stderr, run.returncode
    with open(path, encoding="utf-8") as log:
        return log.read(), 0


def main(argv):
    if "--" in argv:
        split = argv.index("--")
        sources, extra = argv[:split], argv[split + 1:]
    else:
        sources, extra = argv, []
    if not sources:
        print(__doc__.strip().splitlines()[0], file=sys.stderr)
        return 2
    rows = OrderedDict()
    backends = []
    failed_runs = []
    for source in sources:
        text, status = output_of(source, extra)
        if status != 0:
            failed_runs.append(f"{source} exited with status {status}")
        for line in text.splitlines():
            match = LINE.match(line.strip())
            if not match:
                continue
            backend, precision, function, variant, form, ratio, outside, count = match.groups()
            column = f"{'WebGPU' if backend == 'webgpu' else 'WebGL2'}{' ' + precision if precision else ''}"
            if column not in backends:
                backends.append(column)
            # The form without the backend's own words, so that both backends share a row.
            form = re.sub(r"^(compute, )?(\d+) inputs$", r"\2 inputs", form)
            form = re.sub(r"^fragment, dpdx(Fine|Coarse)$", lambda m: f"fragment, {m.group(1).lower()} derivatives", form)
            form = re.sub(r"^fragment quads, (fine|coarse) dFdx$", r"fragment, \1 derivatives", form)
            key = (function, variant, form)
            rows.setdefault(key, {})[column] = (float(ratio), int(outside), int(count))
    print("| function | variant | form | " + " | ".join(f"{b} worst error / bound" for b in backends) + " |")
    print("|---|---|---|" + "---|" * len(backends))
    outside_total = 0
    for (function, variant, form), cells in rows.items():
        shown = []
        for backend in backends:
            if backend not in cells:
                shown.append("")
                continue
            ratio, outside, count = cells[backend]
            outside_total += outside
            shown.append(f"{ratio:.3g}" + (f" ({outside} of {count} outside)" if outside else ""))
        print(f"| {function} | {variant} | {form} | " + " | ".join(shown) + " |")
    for problem in failed_runs:
        print(problem, file=sys.stderr)
    return 1 if outside_total or failed_runs else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
