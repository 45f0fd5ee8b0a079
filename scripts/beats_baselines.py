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


def metric_value(case, name):
    """A case's metric: a number, or the mean of an interval ({"mean", "low", "high"})."""
    value = case[name]
    return value['mean'] if isinstance(value, dict) else value


def scene_means(cases, image_metric='image_error', temporal_metric='flicker_error'):
    """Per scene and configuration: the means of the image and temporal metrics over the alphas,
    no Fresnel (by default the verdict's: image error and flicker error, docs/TEMPORAL.md)."""
    sums = collections.defaultdict(lambda: collections.defaultdict(lambda: [0.0, 0.0, 0]))
    for case in cases:
        if case['fresnel']:
            continue
        entry = sums[case['scene']][case['configuration']]
        entry[0] += metric_value(case, image_metric)
        # TAA cases carry TDE only (docs/TEMPORAL.md: the flicker error is measured without TAA).
        entry[1] += metric_value(case, temporal_metric if temporal_metric in case else 'tde')
        entry[2] += 1
    return {scene: {c: (v[0] / v[2], v[1] / v[2]) for c, v in configs.items()} for scene, configs in sums.items()}


def scene_decisions(table):
    """The bench's per scene x path decisions: (scene, path, chosen, beats every engine too)."""
    for entry in table['decisions']['per_scene']:
        engines = entry['against_engines']
        beats_all = entry['chosen'] != 'none' and all(against['outcome'] == 'beats' for against in engines.values())
        yield entry['scene'], entry['path'], entry['chosen'], beats_all


def main():
    table = json.load(open(sys.argv[1]))
    # The verdict's temporal metric: the video error (10 - ColorVideoVDP's JOD) where measured.
    video = any(case.get('video_error', {}).get('mean', 0.0) > 0.0 for case in table['cases'])
    means = scene_means(table['cases'], temporal_metric='video_error' if video else 'flicker_error')
    wins = rows = 0
    for scene, path, chosen, beats_all in scene_decisions(table):
        rows += 1
        wins += beats_all
        verdict = 'beats' if beats_all else ('no filter' if chosen == 'none' else 'beats none')
        best, none = means[scene][chosen], means[scene]['none']
        print(f"{scene:17s} {path:8s} {verdict:10s} {chosen:48s} image error {best[0]:.4f} (none {none[0]:.4f})  "
              + (f"JOD {10 - best[1]:.2f} (none {10 - none[1]:.2f})" if video else f"flicker error {best[1]:.5f} (none {none[1]:.5f})"))
    print(f"{wins} of {rows} scene x path rows: saagen's decision beats no SAA and every engine form beyond the intervals")


if __name__ == '__main__':
    main()
