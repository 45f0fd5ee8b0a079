#!/usr/bin/env python3
"""Per scene and render path of a `saagen bench --json` table: LDR-FLIP, HDR-FLIP, tonemapped RMSE
and TDE (means over the scene's alphas, no Fresnel) of no SAA, of the best engine form by LDR-FLIP
and of saagen's decision on the scene (the bench's "decisions"; none where nothing beats no SAA),
as a Markdown table (each cell LDR-FLIP / HDR-FLIP / tonemapped RMSE / TDE).

    python3 scripts/row_metrics.py trade.json"""
import json
import sys

from beats_baselines import scene_decisions, scene_means

METRICS = ('flip_ldr', 'flip_hdr', 'rmse_tonemapped')


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    table = json.load(open(sys.argv[1]))
    cases = table['cases']
    decided = {(scene, path): (chosen, beats) for scene, path, chosen, beats in scene_decisions(table)}
    by_metric = {m: scene_means(cases, m) for m in METRICS}
    print('| scene | path | none | best engine | best saagen | |')
    print('|---|---|---|---|---|---|')
    for scene, means in by_metric['flip_ldr'].items():
        engines = {c: v for c, v in means.items() if c.startswith('engine-')}
        engine = min(engines, key=lambda c: engines[c][0])

        def cell(c):
            return ' / '.join(f'{by_metric[m][scene][c][0]:.4f}' for m in METRICS) + f' / {means[c][1]:.5f}'

        for path in ('forward', 'deferred'):
            best, beats = decided[(scene, path)]
            print(f"| {scene} | {path} | {cell('none')} | {engine[len('engine-'):]} {cell(engine)} | {best} {cell(best)} | "
                  f"{'beats' if beats else ('no filter' if best == 'none' else 'beats none only')} |")

if __name__ == '__main__':
    main()
