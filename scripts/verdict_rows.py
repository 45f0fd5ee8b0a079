#!/usr/bin/env python3
"""Rows of a `saagen bench --json` table in the verdict's metrics (docs/TEMPORAL.md): per scene and
configuration, the mean image error (LDR-FLIP of every animation frame) and video error (10 -
ColorVideoVDP's JOD) over the scene's alphas, no Fresnel, and the paired comparison against no SAA
the bench wrote (`comparisons`: the difference with its 95 % interval, and beats / ties / loses /
mixed), as a Markdown table. It reads what the bench measured and compared; it decides nothing.

    python3 scripts/verdict_rows.py T.json [--scene S ...] [--content] [--best PATH=REGEX ...] [CONFIGURATION ...]

--scene      only these scenes (default: every scene of the table)
--content    the per-content comparisons (curved, normal-mapped, ...) instead of the per-scene ones
--best PATH=REGEX
             per scene, of the configurations whose name matches REGEX (Python, whole name), the one
             with the lowest mean video error difference against no SAA, shown as PATH; e.g.
             `--best "forward, tail=forward-.*/tail"`
--decision   per scene, also the bench's own decision on each render path (`decisions.per_scene`,
             saagen/decision.hpp), shown as `PATH decision:`; `none` where nothing beats no SAA
--count REGEX
             instead of rows: per scene, how many configurations matching REGEX beat / tie / lose /
             are mixed against no SAA

e.g. `python3 scripts/verdict_rows.py T.json --scene torus forward-aniso-projected/tail deferred-aniso/tail`.
"""
import collections
import json
import re
import sys


def value(entry, name):
    """A case's metric: a number, or the mean of an interval ({"mean", "low", "high"})."""
    v = entry[name]
    return v['mean'] if isinstance(v, dict) else v


def row_means(cases):
    """(scene, configuration) -> (mean image error, mean video error) over the alphas, no Fresnel."""
    sums = collections.defaultdict(lambda: [0.0, 0.0, 0])
    for case in cases:
        if case['fresnel']:
            continue
        entry = sums[(case['scene'], case['configuration'])]
        entry[0] += value(case, 'image_error')
        entry[1] += value(case, 'video_error')
        entry[2] += 1
    return {key: (s[0] / s[2], s[1] / s[2]) for key, s in sums.items()}


def comparisons(table, scope):
    """(name, configuration) -> the bench's comparison against no SAA."""
    return {(c['name'], c['configuration']): c for c in table['comparisons']
            if c['scope'] == scope and c['baseline'] == 'none'}


def interval(metric, digits):
    return f"{metric['mean']:+.{digits}f} [{metric['low']:+.{digits}f}, {metric['high']:+.{digits}f}]"


def cells(means, compared, name, configuration):
    image, video = means.get((name, configuration), (None, None))
    head = f'{image:.4f} | {video:.2f}' if image is not None else '- | -'
    if configuration == 'none':
        return head + ' | | | (baseline)'
    c = compared.get((name, configuration))
    if c is None:
        return head + ' | - | - | not compared'
    return head + f" | {interval(c['image_error'], 4)} | {interval(c['video_error'], 2)} | {c['outcome']}"


def best_of(compared, name, pattern):
    """The configuration matching pattern with the lowest mean video error difference, or None."""
    found = [(c['video_error']['mean'], conf) for (n, conf), c in compared.items()
             if n == name and re.fullmatch(pattern, conf)]
    return min(found)[1] if found else None


def main(argv):
    args, scenes, bests, configurations, content, count, decision = argv[1:], [], [], [], False, None, False
    if not args:
        sys.exit(__doc__)
    path = args.pop(0)
    while args:
        a = args.pop(0)
        if a == '--scene':
            scenes.append(args.pop(0))
        elif a == '--best':
            label, _, pattern = args.pop(0).partition('=')
            bests.append((label, pattern))
        elif a == '--content':
            content = True
        elif a == '--decision':
            decision = True
        elif a == '--count':
            count = args.pop(0)
        else:
            configurations.append(a)
    table = json.load(open(path))
    scope = 'content' if content else 'scene'
    compared = comparisons(table, scope)
    means = {} if content else row_means(table['cases'])
    if content:  # the per-content rows' means are the bench's by_content entries
        means = {(r['content'], r['configuration']): (r['image_error'], r['video_error']) for r in table['by_content']}
    names = scenes or list(dict.fromkeys(n for n, _ in compared))
    if count:
        print('| scene | beats | ties | mixed | loses |')
        print('|---|---:|---:|---:|---:|')
        for name in names:
            tally = collections.Counter(c['outcome'] for (n, conf), c in compared.items()
                                        if n == name and re.fullmatch(count, conf))
            print(f"| {name} | {tally['beats']} | {tally['ties']} | {tally['mixed']} | {tally['loses']} |")
        return
    print(f"| {scope} | configuration | image error | video error | against no SAA: image | video | outcome |")
    print('|---|---|---:|---:|---:|---:|---|')
    for name in names:
        shown = [('', 'none')] + [('', c) for c in configurations]
        if decision:
            shown += [(f"{d['path']} decision: ", d['chosen']) for d in table['decisions']['per_scene'] if d['scene'] == name]
        shown += [(label + ': ', best_of(compared, name, pattern)) for label, pattern in bests]
        for label, configuration in shown:
            if configuration is None:
                continue
            if label and configuration == 'none':  # a decision that takes nothing
                print(f'| {name} | {label}no filter | | | | | nothing beats no SAA |')
                continue
            print(f'| {name} | {label}{configuration} | {cells(means, compared, name, configuration)} |')


if __name__ == '__main__':
    main(sys.argv)
