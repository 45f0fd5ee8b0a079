#!/usr/bin/env python3
"""The figures of saagen's advice table (generator/include/saagen/advice.hpp, without TAA) from a
trade table: per content type of its "by_content" rows, no SAA and the configurations shaded with
the planner's lobe that beat no SAA in both LDR-FLIP and TDE, lowest LDR-FLIP first (the first five,
as the table keeps them), printed as the table's C++ initialisers.

    saagen bench --preset medium --json T.json && python3 scripts/advice_figures.py T.json [tail]
"""
import json
import sys


def lobe_of(configuration):
    return configuration.split('/')[1] if '/' in configuration else 'papers'


def winners(rows, lobe):
    none = next(r for r in rows if r['configuration'] == 'none')
    beating = [r for r in rows if lobe_of(r['configuration']) == lobe and r['error'] < none['error'] and r['tde'] < none['tde']]
    return none, sorted(beating, key=lambda r: r['error'])[:5]


def figure(row):
    return f'{{"{row["configuration"]}", {row["error"]:.4f}, {row["tde"]:.5f}}}'


def main():
    table = json.load(open(sys.argv[1]))
    lobe = sys.argv[2] if len(sys.argv) > 2 else 'tail'
    contents = sorted({r['content'] for r in table['by_content']})
    for content in contents:
        none, best = winners([r for r in table['by_content'] if r['content'] == content], lobe)
        print(f"{content}: none {figure(none)}")
        print("  {{" + ",\n   ".join(figure(r) for r in best) + "}}" if best else "  {} (no configuration beats no SAA)")


if __name__ == '__main__':
    main()
