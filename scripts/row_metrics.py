#!/usr/bin/env python3
"""Per scene and render path of a `saagen bench --json` table: LDR-FLIP, HDR-FLIP, tonemapped RMSE
and TDE (means over the scene's alphas, no Fresnel) of no SAA, of the best engine form by LDR-FLIP
and of saagen's best configuration as beats_baselines.py chooses it, as a Markdown table (each cell
LDR-FLIP / HDR-FLIP / tonemapped RMSE / TDE).

    python3 scripts/row_metrics.py trade.json [papers|tail|mapped|exact|any]"""
import json
import sys

from beats_baselines import lobe_of, scene_means

METRICS = ('flip_ldr', 'flip_hdr', 'rmse_tonemapped')


def best_saagen(means, path, lobe):
    """beats_baselines.py's choice: the lowest LDR-FLIP among the configurations that beat every
    baseline in LDR-FLIP and TDE, else among all; and whether one beats them."""
    baselines = [v for c, v in means.items() if c == 'none' or c.startswith('engine-')]
    candidates = {c: v for c, v in means.items()
                  if c.startswith(path) and (lobe == lobe_of(c) or (lobe == 'any' and lobe_of(c) != 'exact'))}
    winners = {c: v for c, v in candidates.items() if all(v[0] < b[0] and v[1] < b[1] for b in baselines)}
    pool = winners or candidates
    return min(pool, key=lambda c: pool[c][0]), bool(winners)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    cases = json.load(open(sys.argv[1]))['cases']
    lobe = sys.argv[2] if len(sys.argv) > 2 else 'any'
    by_metric = {m: scene_means(cases, m) for m in METRICS}
    print('| scene | path | none | best engine | best saagen | |')
    print('|---|---|---|---|---|---|')
    for scene, means in by_metric['flip_ldr'].items():
        engines = {c: v for c, v in means.items() if c.startswith('engine-')}
        engine = min(engines, key=lambda c: engines[c][0])

        def cell(c):
            return ' / '.join(f'{by_metric[m][scene][c][0]:.4f}' for m in METRICS) + f' / {means[c][1]:.5f}'

        for path in ('forward', 'deferred'):
            best, beats = best_saagen(means, path, lobe)
            print(f"| {scene} | {path} | {cell('none')} | {engine[len('engine-'):]} {cell(engine)} | {best} {cell(best)} | "
                  f"{'beats' if beats else 'loses'} |")

if __name__ == '__main__':
    main()
