#!/usr/bin/env python3
"""The figures of saagen's advice table (generator/include/saagen/advice.hpp, without TAA) from a
trade table: per content type of its "by_content" rows, no SAA and the usable configurations of the
bench's decisions (its "decisions", saagen/decision.hpp) that beat no SAA on either path, lowest
LDR-FLIP first (the first five, as the table keeps them), printed as the table's C++ initialisers;
the decision itself is the planner's, on these figures.

    saagen bench --preset medium --json T.json && python3 scripts/advice_figures.py T.json
"""
import json
import sys


def winners(table, content):
    rows = {r['configuration']: r for r in table['by_content'] if r['content'] == content}
    beating = {c['configuration'] for d in table['decisions']['by_content'] if d['content'] == content
               for c in d['candidates'] if c['usable'] and c['outcome'] == 'beats'}
    return rows['none'], sorted((rows[c] for c in beating), key=lambda r: r['error'])[:5]


def figure(row):
    return f'{{"{row["configuration"]}", {row["error"]:.4f}, {row["tde"]:.5f}}}'


def main():
    table = json.load(open(sys.argv[1]))
    contents = sorted({r['content'] for r in table['by_content']})
    for content in contents:
        none, best = winners(table, content)
        print(f"{content}: none {figure(none)}")
        print("  {{" + ",\n   ".join(figure(r) for r in best) + "}}" if best else "  {} (no configuration beats no SAA)")


if __name__ == '__main__':
    main()
