#!/usr/bin/env python3
"""Prints the sanity suite of a `saagen bench --json` table as the Markdown table docs/TEMPORAL.md
shows: per scene, each known result's image error / temporal error (the video error, 10 - ColorVideoVDP's
JOD, where the table has it, else the flicker error; means over the scene's alphas), the lag
(x 1e-4) of delayed and of 1-spp no SAA, the verdict's choice with the degenerate results entered,
the alphas where the verdict has not converged (the stable rule: a standing against no SAA changes
with a quarter of the ground truth's samples), and the rules that failed.

    python3 scripts/sanity_table.py T.json

It reads what the bench measured and checked (`sanity`, `sanity_checks`); it checks nothing itself.
"""
import json
import sys

RESULTS = ("other-seed", "quarter-samples", "delayed", "blurred", "frozen", "no-highlight", "none")


def temporal(entry):
    """The entry's temporal error: the video error (JOD loss) where measured, else the flicker error."""
    return f'{entry["video_error"]:.2f}' if "video_error" in entry else f'{entry["flicker_error"]:.5f}'


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: sanity_table.py T.json")
    with open(argv[1]) as f:
        table = json.load(f)
    checks = table["sanity_checks"]
    print("| scene | " + " | ".join("1-spp no SAA" if r == "none" else r for r in RESULTS)
          + " | lag x 1e-4, delayed / no SAA | verdict's choice, degenerates entered | not converged at alpha |")
    print("|---" * (len(RESULTS) + 4) + "|")
    failures = []
    for check in checks:
        by_result = {entry["result"]: entry for entry in check["entries"]}
        cells = [f'{by_result[r]["image_error"]:.4f} / {temporal(by_result[r])}' if r in by_result else "-" for r in RESULTS]
        lags = " / ".join(f'{by_result[r]["lag"] * 1e4:+.2f}' if "lag" in by_result.get(r, {}) else "-" for r in ("delayed", "none"))
        unconverged = ", ".join(f"{alpha:g}" for alpha in check.get("unconverged_alphas", [])) or "-"
        print(f'| {check["scene"]} | ' + " | ".join(cells) + f' | {lags} | {check["verdict_choice"] or "no filter"} | {unconverged} |')
        failures += check["failures"]
    print()
    print(f"{sum(1 for c in checks if c['passed'])} of {len(checks)} scenes pass every rule" + (":" if failures else "."))
    for failure in failures:
        print(f"- {failure}")


if __name__ == "__main__":
    main(sys.argv)
