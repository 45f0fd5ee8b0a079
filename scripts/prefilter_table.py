#!/usr/bin/env python3
"""The normal-map-to-roughness forms against the ground truth, per normal-mapped scene of a
`saagen bench --json` table: for a base configuration, each prefilter form's mean (over the
scene's alphas, no Fresnel) LDR-FLIP, HDR-FLIP, tonemapped RMSE and TDE, lower is better; the
best form per metric in bold, and per metric the best form's margin over the runner-up and
over the worst (docs/PREFILTER.md).

    python3 scripts/prefilter_table.py trade.json [BASE ...]

BASE is a configuration without its prefilter (default `none`: texture prefiltering alone);
e.g. `deferred-avg:geometric/tail` reads the rows `deferred-avg:geometric+FORM/tail`. The
baseline row without a prefilter is BASE itself (for `none`, no SAA).

    python3 scripts/prefilter_table.py --strength BASE S=trade.json ...

The strength sweep: tables measured with `saagen bench --prefilter-scale S`, as one table per
scene of the Toksvig and HDRP rows of BASE by strength c, the multiple of Toksvig's addition
2 (1 - L) / L (Toksvig at scale S is c = S; HDRP at scale S is about c = S / 4, exactly so
below its cap).

    python3 scripts/prefilter_table.py --strength-verdict BASE S=trade.json ...

The same sweep in the verdict's metrics (docs/TEMPORAL.md): per scene and strength, the image
error and video error (means over the alphas) and the paired comparison against no SAA with its
95 % interval and outcome (scripts/verdict_rows.py reads them)."""
import collections
import json
import sys

FORMS = ['toksvig', 'lean', 'unreal', 'filament-vmf', 'hdrp']
METRICS = [('flip_ldr', 'LDR-FLIP'), ('flip_hdr', 'HDR-FLIP'), ('rmse_tonemapped', 'RMSE tonemapped'), ('tde', 'TDE')]


def configuration(base, form):
    """`deferred-avg:geometric/tail` + `hdrp` -> `deferred-avg:geometric+hdrp/tail`."""
    head, slash, lobe = base.partition('/')
    if form:
        head += '+' + form
    return head + (slash + lobe if slash else '')


def means(cases):
    sums = collections.defaultdict(lambda: collections.defaultdict(lambda: collections.defaultdict(float)))
    counts = collections.defaultdict(lambda: collections.defaultdict(int))
    for case in cases:
        if case['fresnel'] or case['configuration'].endswith('+taa'):
            continue
        for key, _ in METRICS:
            sums[case['scene']][case['configuration']][key] += case[key]
        counts[case['scene']][case['configuration']] += 1
    return {s: {c: {k: v / counts[s][c] for k, v in m.items()} for c, m in configs.items()} for s, configs in sums.items()}


def table_for(scene, rows, base):
    names = [('(no prefilter)', configuration(base, ''))] + [(form, configuration(base, form)) for form in FORMS]
    present = [(n, c) for n, c in names if c in rows]
    forms = [(n, c) for n, c in present if n != '(no prefilter)']
    if not forms:
        return None
    lines = [f'{scene}, base `{base}`', '', '| form | ' + ' | '.join(label for _, label in METRICS) + ' |',
             '|---|' + '---:|' * len(METRICS)]
    best = {key: min(forms, key=lambda nc: rows[nc[1]][key])[0] for key, _ in METRICS}
    for name, config in present:
        cells = []
        for key, _ in METRICS:
            text = f'{rows[config][key]:.4f}' if key != 'tde' else f'{rows[config][key]:.5f}'
            cells.append(f'**{text}**' if best[key] == name else text)
        lines.append(f'| {name} | ' + ' | '.join(cells) + ' |')
    lines.append('')
    for key, label in METRICS:
        ranked = sorted(forms, key=lambda nc: rows[nc[1]][key])
        first, second, last = ranked[0], ranked[1] if len(ranked) > 1 else ranked[0], ranked[-1]
        value = rows[first[1]][key]
        lines.append(f'- {label}: {first[0]} best, {rows[second[1]][key] / value:.2f}x lower than {second[0]}, '
                     f'{rows[last[1]][key] / value:.2f}x lower than {last[0]}')
    return '\n'.join(lines)


def strength_tables(base, runs):
    points = collections.defaultdict(dict)  # scene -> (c, label) -> means
    for scale, path in runs:
        for scene, rows in means(json.load(open(path))['cases']).items():
            if configuration(base, '') in rows:
                points[scene][(0.0, 'no prefilter')] = rows[configuration(base, '')]
            for form, factor in (('toksvig', 1.0), ('hdrp', 0.25)):
                if configuration(base, form) in rows:
                    points[scene][(scale * factor, f'{form} x {scale:g}')] = rows[configuration(base, form)]
    for scene, by_c in points.items():
        print(f'{scene}, base `{base}`, strength c = multiple of Toksvig\'s 2 (1 - L) / L\n')
        print('| c | row | ' + ' | '.join(label for _, label in METRICS) + ' |')
        print('|---:|---|' + '---:|' * len(METRICS))
        best = {key: min(by_c, key=lambda k: by_c[k][key]) for key, _ in METRICS}
        for c, label in sorted(by_c):
            cells = []
            for key, _ in METRICS:
                text = f'{by_c[(c, label)][key]:.4f}' if key != 'tde' else f'{by_c[(c, label)][key]:.5f}'
                cells.append(f'**{text}**' if best[key] == (c, label) else text)
            print(f'| {c:.4g} | {label} | ' + ' | '.join(cells) + ' |')
        print()


def strength_verdict_tables(base, runs):
    """The strength sweep in the verdict's metrics: per scene, each (c, row)'s image / video error
    and its comparison with no SAA, from the bench's own `comparisons`."""
    from verdict_rows import cells, comparisons, row_means
    points = collections.defaultdict(dict)  # scene -> (c, label) -> (means, compared, configuration)
    for scale, path in runs:
        table = json.load(open(path))
        means_, compared = row_means(table['cases']), comparisons(table, 'scene')
        for scene in dict.fromkeys(name for name, _ in compared):
            if (scene, configuration(base, '')) in means_:
                points[scene][(0.0, 'no prefilter')] = (means_, compared, configuration(base, ''))
            for form, factor in (('toksvig', 1.0), ('hdrp', 0.25)):
                if (scene, configuration(base, form)) in means_:
                    points[scene][(scale * factor, f'{form} x {scale:g}')] = (means_, compared, configuration(base, form))
    for scene, by_c in points.items():
        if len(by_c) < 2:  # no prefiltered row on this scene (no normal map)
            continue
        print(f'{scene}, base `{base}`, strength c = multiple of Toksvig\'s 2 (1 - L) / L\n')
        print('| c | row | image error | video error | against no SAA: image | video | outcome |')
        print('|---:|---|---:|---:|---:|---:|---|')
        for c, label in sorted(by_c):
            means_, compared, config = by_c[(c, label)]
            print(f'| {c:.4g} | {label} | {cells(means_, compared, scene, config)} |')
        print()


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    if sys.argv[1] == '--strength-verdict':
        runs = [(float(arg.split('=', 1)[0]), arg.split('=', 1)[1]) for arg in sys.argv[3:]]
        strength_verdict_tables(sys.argv[2], runs)
        return
    if sys.argv[1] == '--strength':
        runs = [(float(arg.split('=', 1)[0]), arg.split('=', 1)[1]) for arg in sys.argv[3:]]
        strength_tables(sys.argv[2], runs)
        return
    bases = sys.argv[2:] or ['none']
    all_means = means(json.load(open(sys.argv[1]))['cases'])
    for scene, rows in all_means.items():
        for base in bases:
            text = table_for(scene, rows, base)
            if text:
                print(text + '\n')


if __name__ == '__main__':
    main()
