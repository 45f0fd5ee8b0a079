#!/usr/bin/env python3
"""Per GPU suite x device: tests run / passed / unsupported, the worst error as a fraction of its
bound, and the validation-layer message count, from ctest's JUnit output.

    ctest --test-dir build -L vulkan -j2 --output-junit gpu.xml; python3 scripts/gpu_table.py build/gpu.xml

Suites and devices come from the test names ("<device>.<Suite>.<Test>") and from the one
"[ bound    ] <executable>: ..." line each GoogleTest run prints (tests/support/vulkan_validation.cpp).
"""
import re
import sys
import xml.etree.ElementTree as ET
from collections import defaultdict

BOUND = re.compile(r"\[ bound    \] (\S+): (?:no bounded comparisons|.*worst \|got - expected\| / bound = ([0-9.eE+-]*[0-9]))")
VALIDATION = re.compile(r"^\[validation\] (error|warning):", re.M)
UNSUPPORTED = re.compile(r"^(unsupported on [^\n]*)", re.M)


def main(path):
    root = ET.parse(path).getroot()
    rows = defaultdict(lambda: {"run": 0, "passed": 0, "unsupported": 0, "known": 0, "failed": 0, "worst": None, "validation": 0, "time": 0.0,
                                "notes": set()})
    for case in root.iter("testcase"):
        name = case.get("name", "")
        device, _, rest = name.partition(".")
        if device not in ("lavapipe", "swiftshader"):
            continue  # CPU-only tests
        out = "".join(e.text or "" for e in case.iter("system-out"))
        suite = None
        worst = None
        for match in BOUND.finditer(out):
            suite = match.group(1)
            if match.group(2):
                worst = float(match.group(2))
        if suite is None:
            suite = rest.split(".")[0] if rest.startswith("bench_") else "(" + rest.split(".")[0] + ")"
        row = rows[(suite, device)]
        row["run"] += 1
        row["time"] += float(case.get("time", "0") or 0)
        row["validation"] += len(VALIDATION.findall(out))
        failed = case.find("failure") is not None or case.get("status") == "fail"
        disabled = case.get("status") == "disabled"  # a known failure on this device (tests/CMakeLists.txt)
        skipped = case.find("skipped") is not None or case.get("status") == "notrun"
        if failed:
            row["failed"] += 1
        elif disabled:
            row["known"] += 1
        elif skipped or UNSUPPORTED.search(out):
            row["unsupported"] += 1
            for note in UNSUPPORTED.findall(out):
                row["notes"].add(note.split(":", 1)[1].strip()[:40])
        else:
            row["passed"] += 1
        if worst is not None:
            row["worst"] = worst if row["worst"] is None else max(row["worst"], worst)
    print("| suite | device | run | passed | unsupported | known failures | failed | worst error / bound | validation msgs | time s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    total_validation = 0
    for (suite, device), r in sorted(rows.items()):
        worst = "n/a" if r["worst"] is None else f"{r['worst']:.3g}"
        notes = f" ({', '.join(sorted(r['notes']))})" if r["notes"] else ""
        total_validation += r["validation"]
        print(f"| {suite} | {device} | {r['run']} | {r['passed']} | {r['unsupported']}{notes} | {r['known']} | {r['failed']} | {worst} | {r['validation']} | {r['time']:.0f} |")
    print(f"\nvalidation-layer messages over all runs: {total_validation}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "build/gpu.xml")
