#!/usr/bin/env python3
"""The kernel under TAA: per scene, from `saagen bench --taa --json` tables measured at several
--sigma2 (or other settings), none, none+taa, each engine form under TAA and, per table, the best
saagen configuration without TAA and under TAA by mean LDR-FLIP of the animation, with their TDE,
and whether the one under TAA beats none+taa and every engine+taa in both (means over the
scene's alphas, no Fresnel); then the best under TAA of each lobe (papers', tail-preserving,
mapped) and, on normal-mapped scenes, the best texture prefilter (bake) alone under TAA.

    python3 scripts/taa_kernel.py LABEL=trade.json [LABEL=trade.json ...]

e.g. 0.25=out/taa.json 0.125=out/taa-0.125.json 0.0625=out/taa-0.0625.json. The engine rows do
not depend on --sigma2 (each engine keeps its own constants): they are read from the first table."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from beats_baselines import scene_means  # noqa: E402


def is_taa(configuration):
    """Under TAA: '+taa' before any lobe suffix ('deferred-aniso+taa/tail')."""
    return '+taa' in configuration


def is_saagen_taa(configuration):
    return is_taa(configuration) and not configuration.startswith(('none', 'engine-'))


# The lobes of the +taa rows (trade.hpp, configuration_id: '/tail', '/mapped' after '+taa').
LOBES = [('papers', lambda c: '/' not in c), ('tail', lambda c: c.endswith('/tail')), ('mapped', lambda c: c.endswith('/mapped'))]


def main():
    tables = []
    for argument in sys.argv[1:]:
        label, _, path = argument.partition('=')
        document = json.load(open(path))
        if 'taa_cases' not in document:
            sys.exit(f"{path}: no taa_cases (run saagen bench with --taa)")
        tables.append((label, scene_means(document['taa_cases'], 'flip_ldr_animation')))
    if not tables:
        sys.exit(__doc__)
    first = tables[0][1]
    for scene, means in first.items():
        engines = {c: v for c, v in means.items() if c.startswith('engine-') and is_taa(c)}
        engine, (engine_flip, engine_tde) = min(engines.items(), key=lambda e: e[1][0])
        print(f"{scene}: none {means['none'][0]:.4f} / {means['none'][1]:.5f}, none+taa {means['none+taa'][0]:.4f} / "
              f"{means['none+taa'][1]:.5f}, best engine+taa by LDR-FLIP {engine} {engine_flip:.4f} / {engine_tde:.5f} "
              f"(LDR-FLIP / TDE)")
        baselines = [means['none+taa']] + list(engines.values())
        for label, table in tables:
            plain = {c: v for c, v in table[scene].items() if not is_taa(c) and not c.startswith(('none', 'engine-'))}
            plain_best = min(plain, key=lambda c: plain[c][0])
            print(f"  {label:>8}: {plain_best:40s} {plain[plain_best][0]:.4f} / {plain[plain_best][1]:.5f}  (best saagen without TAA)")
            candidates = {c: v for c, v in table[scene].items() if is_saagen_taa(c)}
            best = min(candidates, key=lambda c: candidates[c][0])
            flip, tde = candidates[best]
            beats_flip = all(flip < b[0] for b in baselines)
            beats_tde = all(tde < b[1] for b in baselines)
            verdict = 'beats both' if beats_flip and beats_tde else 'beats in LDR-FLIP only' if beats_flip else \
                'beats in TDE only' if beats_tde else 'loses'
            print(f"  {label:>8}: {best:40s} {flip:.4f} / {tde:.5f}  {verdict}")
            for lobe, in_lobe in LOBES:
                lobe_rows = {c: v for c, v in candidates.items() if in_lobe(c)}
                if lobe_rows and len(lobe_rows) < len(candidates):
                    lobe_best = min(lobe_rows, key=lambda c: lobe_rows[c][0])
                    print(f"  {label:>8}:   {lobe:>6} lobe: {lobe_best:40s} {lobe_rows[lobe_best][0]:.4f} / {lobe_rows[lobe_best][1]:.5f}")
            bakes = {c: v for c, v in table[scene].items() if is_taa(c) and c.startswith('none+') and c != 'none+taa'}
            if bakes:
                bake = min(bakes, key=lambda c: bakes[c][0])
                print(f"  {label:>8}:   {'bake alone':>11}: {bake:35s} {bakes[bake][0]:.4f} / {bakes[bake][1]:.5f}")


if __name__ == '__main__':
    main()
