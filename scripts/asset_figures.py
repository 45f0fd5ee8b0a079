#!/usr/bin/env python3
"""Per scene of a `saagen bench --json` table (the asset scenes, docs/GLTF_SCENES.md "Figures"):
no SAA, per render path the saagen configuration of the tail-preserving lobe with the lowest mean
LDR-FLIP, and the engine forms with the lowest LDR-FLIP and the lowest TDE (means over the scene's
alphas, no Fresnel; LDR-FLIP / TDE), as a Markdown table: the older figures of docs/GLTF_SCENES.md,
before the video metric (the verdict's metrics with intervals: scripts/verdict_rows.py).

    saagen bench --preset medium --scene ClearCoatTest --scene 2CylinderEngine --json T.json
    python3 scripts/asset_figures.py T.json [SCENE ...]
"""
import collections
import json
import sys


def scene_means(cases):
    sums = collections.defaultdict(lambda: collections.defaultdict(lambda: [0.0, 0.0, 0]))
    for case in cases:
        if case['fresnel']:
            continue
        entry = sums[case['scene']][case['configuration']]
        entry[0] += case['flip_ldr']
        entry[1] += case['tde']
        entry[2] += 1
    return {scene: {c: (v[0] / v[2], v[1] / v[2]) for c, v in configs.items()} for scene, configs in sums.items()}


def lowest(means, keep, index=0):
    return min(((c, v) for c, v in means.items() if keep(c)), key=lambda cv: cv[1][index])


def main():
    by_scene = scene_means(json.load(open(sys.argv[1]))['cases'])
    scenes = sys.argv[2:] or list(by_scene)
    print('| scene | none | forward: lowest LDR-FLIP (tail lobe) | deferred: lowest LDR-FLIP (tail lobe) '
          '| best engine in LDR-FLIP / in TDE |')
    print('|---|---|---|---|---|')
    for scene in scenes:
        means = by_scene[scene]
        none = means['none']
        cells = [f'{scene}', f'{none[0]:.4f} / {none[1]:.5f}']
        for path in ('forward-', 'deferred-'):
            c, v = lowest(means, lambda c: c.startswith(path) and c.endswith('/tail'))
            cells.append(f'`{c}` {v[0]:.4f} / {v[1]:.5f}')
        image = lowest(means, lambda c: c.startswith('engine-'))
        motion = lowest(means, lambda c: c.startswith('engine-'), 1)
        cells.append(f'{image[0]} {image[1][0]:.4f} / {motion[0]} {motion[1][1]:.5f}')
        print('| ' + ' | '.join(cells) + ' |')


if __name__ == '__main__':
    main()
