#!/usr/bin/env python3
"""Per cell (one scene at one alpha) of a `saagen bench --json` table: where saagen's decision for
a content and render path ("decisions" -> "by_content", made by the one decision function,
saagen/decision.hpp) loses to no SAA, or is mixed, on one of that content's scenes at one
roughness. The bench writes each cell's paired comparison with no SAA ("comparisons", scope
"cell": its 95 % interval is over that cell's frames and ground-truth seeds only, so a cell says
more about one roughness than the per-content verdict, and less certainly). This script decides
nothing; it lists what the per-content verdict pools away.

    python3 scripts/cell_verdicts.py trade.json
"""
import collections
import json
import sys


def interval(metric):
    """The difference with its 95 % interval, and the bench's outcome for that metric (a difference
    within the ground truth's own noise, or one whose call the bias of the ground truth's samples
    would change, is a tie whatever its interval: "tie: ground truth's noise", "tie: ground truth's
    samples")."""
    text = f"{metric['mean']:+.4g} [{metric['low']:+.4g}, {metric['high']:+.4g}]"
    if metric.get('ground_truth_limited'):
        return text + " (tie: ground truth's noise)"
    if metric.get('bias_limited'):
        return text + " (tie: ground truth's samples)"
    return text + (f" ({metric['outcome']})" if 'outcome' in metric else "")


def temporal(comparison):
    return comparison.get('video_error', comparison['flicker_error'])


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[-1].strip())
        return 2
    with open(argv[1]) as f:
        table = json.load(f)
    cells = collections.defaultdict(list)  # (scene, configuration) -> cell comparisons
    for c in table['comparisons']:
        if c['scope'] == 'cell' and c['baseline'] == 'none':
            cells[(c['name'], c['configuration'])].append(c)
    if not cells:
        print(f"{argv[1]}: no per-cell comparisons (a table written before the bench wrote them)")
        return 1
    scenes_of = collections.defaultdict(set)
    for entry in table['decisions']['per_scene']:
        scenes_of[entry['content']].add(entry['scene'])
    total = counted = 0
    for decision in table['decisions']['by_content']:
        chosen = decision.get('chosen')
        if not chosen or chosen == 'none':
            continue
        outcomes = collections.Counter()
        bad = []
        for scene in sorted(scenes_of[decision['content']]):
            for c in sorted(cells.get((scene, chosen), []), key=lambda c: c['alpha']):
                outcomes[c['outcome']] += 1
                if c['outcome'] in ('loses', 'mixed'):
                    bad.append(c)
        counted += sum(outcomes.values())
        total += len(bad)
        print(f"{decision['content']:<14} {decision['path']:<9} {chosen:<40} cells: " +
              ", ".join(f"{outcomes[o]} {o}" for o in ('beats', 'ties', 'mixed', 'loses')))
        for c in bad:
            print(f"    {c['name']:<22} alpha {c['alpha']:<7g} {c['outcome']:<6} image {interval(c['image_error'])}"
                  f"  temporal {interval(temporal(c))}")
    print(f"{total} of {counted} cells of the decisions lose to no SAA or are mixed beyond their intervals")
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
