#!/usr/bin/env python3
"""Per scene of a `saagen bench --json` table: mean LDR-FLIP / TDE (over the scene's alphas, no
Fresnel) of the named configurations, of no SAA and of the best engine form by LDR-FLIP, as a
Markdown table (the older figures of docs/DEFERRED_KERNEL.md, before the video metric; the verdict's
metrics with intervals: scripts/verdict_rows.py).

    python3 scripts/configuration_means.py trade.json CONFIGURATION...

e.g. `python3 scripts/configuration_means.py trade.json deferred-aniso/tail deferred-avg/tail
forward-aniso-projected/tail`."""
import json
import sys

from beats_baselines import scene_means


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    table = json.load(open(sys.argv[1]))
    names = sys.argv[2:] + ['none']
    print('| scene | ' + ' | '.join(names) + ' | best engine |')
    print('|---|' + '---:|' * (len(names) + 1))
    for scene, means in scene_means(table['cases']).items():
        engines = {c: v for c, v in means.items() if c.startswith('engine-')}
        best = min(engines, key=lambda c: engines[c][0])
        cells = [f'{means[n][0]:.4f} / {means[n][1]:.5f}' if n in means else '-' for n in names]
        print(f'| {scene} | ' + ' | '.join(cells) + f' | {best[len("engine-"):]} {engines[best][0]:.4f} / {engines[best][1]:.5f} |')


if __name__ == '__main__':
    main()
