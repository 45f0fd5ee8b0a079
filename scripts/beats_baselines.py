#!/usr/bin/env python3
"""Per scene and render path of a `saagen bench --json` table: saagen's decision on that scene
(the "decisions" the bench writes, made by the one decision function, saagen/decision.hpp: the
configuration that beats no SAA with the largest LDR-FLIP gain, or none), and whether it also
beats every engine form on that scene; then how many of the scene x path rows beat no SAA and
every engine. This script decides nothing itself.

    python3 scripts/beats_baselines.py trade.json
"""
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


def scene_decisions(table):
    """The bench's per scene x path decisions: (scene, path, chosen, beats every engine too)."""
    for entry in table['decisions']['per_scene']:
        engines = entry['against_engines']
        beats_all = entry['chosen'] != 'none' and all(outcome == 'beats' for outcome in engines.values())
        yield entry['scene'], entry['path'], entry['chosen'], beats_all


def main():
    table = json.load(open(sys.argv[1]))
    means = scene_means(table['cases'])
    wins = rows = 0
    for scene, path, chosen, beats_all in scene_decisions(table):
        rows += 1
        wins += beats_all
        verdict = 'beats' if beats_all else ('no filter' if chosen == 'none' else 'beats none')
        best, none = means[scene][chosen], means[scene]['none']
        print(f"{scene:17s} {path:8s} {verdict:10s} {chosen:48s} LDR-FLIP {best[0]:.4f} (none {none[0]:.4f})  "
              f"TDE {best[1]:.5f} (none {none[1]:.5f})")
    print(f"{wins} of {rows} scene x path rows: saagen's decision beats no SAA and every engine form in LDR-FLIP and TDE")


if __name__ == '__main__':
    main()
