#!/usr/bin/env python3
"""Per scene and render path of a `saagen bench --json` table: the best saagen configuration by
mean LDR-FLIP among those that beat no SAA and every engine form in both LDR-FLIP and TDE (means
over the scene's alphas, no Fresnel), and how many of the scene x path rows have one.

    python3 scripts/beats_baselines.py trade.json [papers|tail|mapped|exact|any]

The optional lobe restricts saagen's configurations to one lobe (`VARIANT/tail`, ...; papers:
no suffix). `any` leaves out the exact lobe (`saagen bench --exact-lobe`), a measurement that no
target emits."""
import collections
import json
import sys


def lobe_of(configuration):
    return configuration.split('/')[1] if '/' in configuration else 'papers'


def scene_means(cases, image_metric='flip_ldr'):
    """Per scene and configuration: the means of image_metric and TDE over the alphas, no Fresnel."""
    sums = collections.defaultdict(lambda: collections.defaultdict(lambda: [0.0, 0.0, 0]))
    for case in cases:
        if case['fresnel']:
            continue
        entry = sums[case['scene']][case['configuration']]
        entry[0] += case[image_metric]
        entry[1] += case['tde']
        entry[2] += 1
    return {scene: {c: (v[0] / v[2], v[1] / v[2]) for c, v in configs.items()} for scene, configs in sums.items()}


def main():
    table = json.load(open(sys.argv[1]))
    lobe = sys.argv[2] if len(sys.argv) > 2 else 'any'
    wins = rows = 0
    for scene, means in scene_means(table['cases']).items():
        baselines = [v for c, v in means.items() if c == 'none' or c.startswith('engine-')]
        for path in ('forward', 'deferred'):
            candidates = {c: v for c, v in means.items()
                          if c.startswith(path) and (lobe == lobe_of(c) or (lobe == 'any' and lobe_of(c) != 'exact'))}
            winners = {c: v for c, v in candidates.items() if all(v[0] < b[0] and v[1] < b[1] for b in baselines)}
            pool = winners or candidates
            best = min(pool, key=lambda c: pool[c][0])
            rows += 1
            wins += bool(winners)
            print(f"{scene:17s} {path:8s} {'beats' if winners else 'loses'} {best:48s} LDR-FLIP {means[best][0]:.4f} "
                  f"(none {means['none'][0]:.4f})  TDE {means[best][1]:.5f} (none {means['none'][1]:.5f})")
    print(f"{wins} of {rows} scene x path rows: the best saagen configuration ({lobe}) beats no SAA and every engine "
          f"form in LDR-FLIP and TDE")


if __name__ == '__main__':
    main()
