#!/usr/bin/env python3
"""The include graph of every folder: its floors, the modules in each, cycles and upward includes.

    python3 scripts/include_graph.py [ROOT]          # print the graph and the figures
    python3 scripts/include_graph.py --check [ROOT]  # exit 1 on a cycle, an upward include, an
                                                     # include into a leaf or a folder with no place
    python3 scripts/include_graph.py --self-test     # the rules on a small tree made in a temporary folder

Every C and C++ file of the repository (tracked or not ignored, build folders left out) belongs to
a module: a source file and its header (generator/<wing>/<name>.cpp with
generator/include/saagen/<wing>/<name>.hpp; <folder>/src/<name>.cpp with
<folder>/include/saagen/<folder>/<name>.hpp elsewhere). A module's floor is its wing in generator/
or its top-level folder (measure/, the measurement wing, sits above reference/, the formulas' oracle).
The floors are ordered, lowest first (FLOORS): a module may include its own floor and the floors
below it, never one above, and no two modules may include each other through any chain. The leaves
(LEAVES: benchmarks, tests, fuzz targets, examples) may include every floor; nothing outside a leaf
includes it. A top-level folder holding C or C++ that is neither a floor nor a leaf fails --check
until it is given a place here. ctest runs the check (tests/CMakeLists.txt); docs/ARCHITECTURE.md
describes the floors and the output.
"""
import collections
import os
import re
import subprocess
import sys

# The library's wings (generator/<wing>/), lowest first.
WINGS = ['base', 'io', 'front', 'target', 'print', 'emit', 'validate', 'products', 'scene', 'integrate']
# Every floor, lowest first: the library's wings, then the folders above them.
FLOORS = WINGS + ['reference', 'measure', 'harness', 'report', 'cli']
# Sub-folders that are floors of their own: <folder>/src/<sub>/ and <folder>/include/saagen/<folder>/<sub>/
# (none at present: measure/, once reference/render/, is a top-level folder).
SUB_FLOORS = {}
# Folders that only use the floors: nothing outside them includes them.
LEAVES = ['bench', 'tests', 'fuzz', 'examples']
# Cycles that were there when the check first covered these folders, each to be broken by the work
# that moves its files: reported, not failed on. A cycle not listed fails --check; a listed one
# that is gone is reported so that its line can be removed.
KNOWN_CYCLES = []
SUFFIXES = ('.cpp', '.hpp', '.h', '.c', '.cc', '.inl')
SKIPPED = ('build', 'node_modules', 'out', 'shared')
INCLUDE = re.compile(r'^\s*#\s*include\s+[<"]([^>"]+)[>"]', re.M)
LITERAL = re.compile(r'R"\((?:.|\n)*?\)"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])\'')  # raw, string and char literals
FUNCTION = re.compile(r'^[A-Za-z][^;{}()]*\b(\w+)\([^;]*\)\s*(const\s*)?(->[^{;]*)?\{\s*$', re.M)


def module_of(path):
    """(floor, name) of a file, relative to the repository root."""
    parts = path.split('/')
    name = os.path.splitext(parts[-1])[0]
    top = parts[0]
    if top == 'generator':
        if parts[1] == 'include':
            return ('base', name) if len(parts) == 4 else (parts[3], name)
        return parts[1], name
    rest = parts[1:]
    if rest[:3] == ['include', 'saagen', top]:
        rest = rest[3:]
    elif rest[:2] == ['include', 'saagen']:
        rest = rest[2:]
    elif rest[:1] == ['src']:
        rest = rest[1:]
    if len(rest) > 1 and rest[0] in SUB_FLOORS.get(top, ()):
        return f'{top}/{rest[0]}', os.path.splitext('/'.join(rest[1:]))[0]
    return top, os.path.splitext('/'.join(rest))[0]


def top_folder(floor):
    return 'generator' if floor in WINGS else floor.split('/')[0]


def source_files(root):
    """Every C and C++ file: git's tracked and not-ignored files, or a walk outside the build folders."""
    try:
        listed = subprocess.run(['git', '-C', root, 'ls-files', '--cached', '--others', '--exclude-standard'],
                                capture_output=True, text=True, check=True).stdout.split('\n')
        paths = [p for p in listed if '/' in p and p.endswith(SUFFIXES) and os.path.exists(os.path.join(root, p))]
    except (OSError, subprocess.CalledProcessError):
        paths = []
        for folder, folders, names in os.walk(root):
            folders[:] = [f for f in folders if not f.startswith('.') and not f.startswith(SKIPPED)]
            paths += [os.path.relpath(os.path.join(folder, n), root) for n in names if n.endswith(SUFFIXES)]
        paths = [p for p in paths if '/' in p]
    return sorted(set(p for p in paths if not p.split('/')[0].startswith(SKIPPED)))


def header_index(files):
    """Include spelling -> file: "saagen/<wing>/<name>.hpp" and "saagen/report/<name>.hpp"."""
    index = {}
    for path in files:
        parts = path.split('/')
        if 'include' in parts:
            index['/'.join(parts[parts.index('include') + 1:])] = path
    return index


def module_namer(files):
    """module_of, except that a header at the top of include/saagen/ whose name is a source file's
    belongs to that source's module (the flat layout before the wings)."""
    sources = collections.defaultdict(set)
    for path in files:
        if path.endswith('.cpp') and path.startswith('generator/'):
            sources[module_of(path)[1]].add(module_of(path))
    def namer(path):
        module = module_of(path)
        if module[0] == 'base' and len(sources.get(module[1], ())) == 1:
            return next(iter(sources[module[1]]))
        return module
    return namer


def module_graph(root):
    files = list(source_files(root))
    known = set(files)
    index = header_index(files)
    module_of = module_namer(files)
    graph = collections.defaultdict(set)
    lines = {}
    for path in files:
        text = open(os.path.join(root, path), encoding='utf-8', errors='replace').read()
        lines[path] = text.count('\n')
        source = module_of(path)
        graph[source]
        for spelled in INCLUDE.findall(text):
            target = index.get(spelled)
            if target is None:
                local = os.path.normpath(os.path.join(os.path.dirname(path), spelled))
                target = local if local in known else None
            if target is None and path.split('/')[0] in LEAVES:
                # A leaf's own root is on its include path: tests/ spells its shared helpers
                # "support/<name>.hpp" from any of its folders (tests/CMakeLists.txt).
                rooted = os.path.normpath(os.path.join(path.split('/')[0], spelled))
                target = rooted if rooted in known else None
            if target is not None and module_of(target) != source:
                graph[source].add(module_of(target))
    return graph, lines


def cycles(graph):
    """Strongly connected components with more than one module (Tarjan)."""
    order, low, on_stack, stack, found = {}, {}, set(), [], []

    def visit(node):
        order[node] = low[node] = len(order)
        stack.append(node)
        on_stack.add(node)
        for next_node in sorted(graph.get(node, ())):
            if next_node not in order:
                visit(next_node)
                low[node] = min(low[node], low[next_node])
            elif next_node in on_stack:
                low[node] = min(low[node], order[next_node])
        if low[node] == order[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in order:
            visit(node)
    return found


def rank(floor):
    """The floor's place, lowest first; every leaf above every floor; None for a folder with no place."""
    if floor in FLOORS:
        return FLOORS.index(floor)
    if floor in LEAVES:
        return len(FLOORS)
    return None


def unplaced(graph):
    return sorted(set(top_folder(module[0]) for module in graph if rank(module[0]) is None))


def upward_includes(graph):
    """(a, b): a includes b of a higher floor, or b is in a leaf other than a's folder."""
    found = []
    for a, targets in graph.items():
        for b in targets:
            if rank(a[0]) is None or rank(b[0]) is None or a[0] == b[0]:
                continue
            if rank(b[0]) > rank(a[0]) or b[0] in LEAVES:
                found.append((a, b))
    return sorted(found)


def longest_functions(root, files, count):
    sizes = []
    for path in files:
        if not path.endswith(('.cpp', '.c', '.cc')):
            continue
        text = LITERAL.sub('""', open(os.path.join(root, path), encoding='utf-8', errors='replace').read())
        for match in FUNCTION.finditer(text):
            depth, end = 0, match.end() - 1
            for end in range(match.end() - 1, len(text)):
                depth += {'{': 1, '}': -1}.get(text[end], 0)
                if depth == 0:
                    break
            sizes.append((text.count('\n', match.start(), end) + 1, f'{path}: {match.group(1)}'))
    return sorted(sizes, reverse=True)[:count]


def name(module):
    return f'{module[0]}/{module[1]}'


def folder_figures(graph, lines, found, upward):
    """Per top-level folder: files, lines, modules, the folders it includes, cycles and upward includes."""
    figures = collections.OrderedDict()
    tops = sorted(set(p.split('/')[0] for p in lines), key=lambda t: (rank(t if t != 'generator' else WINGS[0]) is None,
                                                                        min([rank(f) for f in FLOORS + LEAVES if top_folder(f) == t] or [99]), t))
    for top in tops:
        modules = [m for m in graph if top_folder(m[0]) == top]
        figures[top] = {
            'files': sum(1 for p in lines if p.split('/')[0] == top),
            'lines': sum(n for p, n in lines.items() if p.split('/')[0] == top),
            'modules': len(modules),
            'includes': sorted(set(top_folder(b[0]) for m in modules for b in graph[m]) - {top}),
            'cycles': sum(1 for component in found if any(top_folder(m[0]) == top for m in component)),
            'upward': sum(1 for a, _ in upward if top_folder(a[0]) == top),
        }
    return figures


def self_test():
    """Each rule on a made-up tree: a lower wing including a higher one, a floor including a test, a
    test including a benchmark, a new cycle, a folder with no place; and a clean tree passing."""
    import tempfile

    def verdict(files):
        with tempfile.TemporaryDirectory() as root:
            for path, text in files.items():
                os.makedirs(os.path.join(root, os.path.dirname(path)), exist_ok=True)
                with open(os.path.join(root, path), 'w') as out:
                    out.write(text)
            graph, _ = module_graph(root)
            known = [list(map(name, c)) for c in cycles(graph)]
            return [c for c in known if c not in KNOWN_CYCLES], upward_includes(graph), unplaced(graph)

    clean = {
        'generator/io/input.cpp': '#include "saagen/io/input.hpp"\n',
        'generator/include/saagen/io/input.hpp': '#pragma once\n',
        'generator/emit/emitter.cpp': '#include "saagen/emit/emitter.hpp"\n#include <saagen/io/input.hpp>\n',
        'generator/include/saagen/emit/emitter.hpp': '#pragma once\n',
        'measure/src/scene.cpp': '#include "saagen/measure/scene.hpp"\n',
        'measure/include/saagen/measure/scene.hpp': '#include "saagen/reference/math.hpp"\n',
        'reference/include/saagen/reference/math.hpp': '#pragma once\n',
        'harness/src/shader.cpp': '#include <saagen/emit/emitter.hpp>\n#include "local.hpp"\n',
        'harness/src/local.hpp': '#pragma once\n',
        'tests/support.hpp': '#pragma once\n',
        'tests/io/test_input.cpp': '#include "../support.hpp"\n#include "saagen/io/input.hpp"\n#include "saagen/measure/scene.hpp"\n',
        'bench/bench_emit.cpp': '#include "saagen/emit/emitter.hpp"\n',
    }
    failures = []

    def expect(label, files, cycles_, upward_, homeless_):
        found, upward, homeless = verdict(files)
        got = (len(found), [(name(a), name(b)) for a, b in upward], homeless)
        if got != (cycles_, upward_, homeless_):
            failures.append(f'{label}: expected {(cycles_, upward_, homeless_)}, got {got}')

    expect('clean tree', clean, 0, [], [])
    expect('lower wing includes a higher one',
           dict(clean, **{'generator/io/input.cpp': '#include "saagen/emit/emitter.hpp"\n'}), 1, [('io/input', 'emit/emitter')], [])
    expect('the oracle includes the measurement',
           dict(clean, **{'reference/include/saagen/reference/math.hpp': '#include "saagen/measure/scene.hpp"\n'}),
           1, [('reference/math', 'measure/scene')], [])
    expect('a floor includes a test helper',
           dict(clean, **{'harness/src/local.hpp': '#include "../../tests/support.hpp"\n'}), 0, [('harness/local', 'tests/support')], [])
    expect('a test includes a benchmark',
           dict(clean, **{'tests/support.hpp': '#include "../bench/bench_emit.cpp"\n'}), 0, [('tests/support', 'bench/bench_emit')], [])
    expect('a cycle between two modules of one wing',
           dict(clean, **{'generator/include/saagen/io/input.hpp': '#include "saagen/io/output.hpp"\n',
                          'generator/include/saagen/io/output.hpp': '#include "saagen/io/input.hpp"\n'}), 1, [], [])
    expect('a folder with no place', dict(clean, **{'attic/src/trade.cpp': '#include <saagen/io/input.hpp>\n'}), 0, [], ['attic'])
    expect('two test helpers spelt from the leaf\'s root include each other',
           dict(clean, **{'tests/support/a.hpp': '#include "support/b.hpp"\n', 'tests/support/b.hpp': '#include "support/a.hpp"\n'}),
           1, [], [])
    for failure in failures:
        print('include_graph self-test: ' + failure)
    print(f'include_graph self-test: {8 - len(failures)} passed, {len(failures)} failed')
    sys.exit(1 if failures else 0)


def main():
    if '--self-test' in sys.argv:
        self_test()
    arguments = [a for a in sys.argv[1:] if a != '--check']
    root = arguments[0] if arguments else os.path.join(os.path.dirname(__file__), '..')
    graph, lines = module_graph(root)
    found, upward, homeless = cycles(graph), upward_includes(graph), unplaced(graph)
    order = ', '.join(FLOORS) + '; leaves: ' + ', '.join(LEAVES)
    known = [c for c in found if list(map(name, c)) in KNOWN_CYCLES]
    new = [c for c in found if c not in known]
    gone = [c for c in KNOWN_CYCLES if c not in [list(map(name, f)) for f in found]]
    if '--check' in sys.argv:
        for component in known:
            print('known include cycle (KNOWN_CYCLES): ' + ' <-> '.join(map(name, component)))
        for component in gone:
            print('no longer a cycle: remove it from KNOWN_CYCLES: ' + ' <-> '.join(component))
        for component in new:
            print('include cycle: ' + ' <-> '.join(map(name, component)))
        for a, b in upward:
            what = 'a leaf' if b[0] in LEAVES else 'a higher floor'
            print(f'upward include: {name(a)} includes {name(b)}, {what} (floors, lowest first: {order})')
        for folder in homeless:
            print(f'{folder}/ holds C or C++ but has no place among the floors and leaves: add it to FLOORS or LEAVES '
                  f'in scripts/include_graph.py and docs/ARCHITECTURE.md')
        print(f'include graph: {len(lines)} files, {len(graph)} modules, {len(found)} cycles ({len(known)} known), '
              f'{len(upward)} upward includes, {len(homeless)} folders without a place')
        sys.exit(1 if new or upward or homeless else 0)
    print('files per folder:')
    per_folder = collections.Counter(os.path.dirname(p) for p in lines)
    for folder, count in sorted(per_folder.items()):
        print(f'  {folder:40s} {count:3d} files {sum(n for p, n in lines.items() if os.path.dirname(p) == folder):6d} lines')
    print('floor dependencies (floors lowest first, then the leaves):')
    floor_edges = collections.defaultdict(set)
    for a, targets in graph.items():
        floor_edges[a[0]]
        for b in targets:
            if a[0] != b[0]:
                floor_edges[a[0]].add(b[0])
    by_rank = lambda floor: (rank(floor) is None, rank(floor) or 0, floor)
    for floor in sorted(floor_edges, key=by_rank):
        print(f'  {floor:16s} -> {", ".join(sorted(floor_edges[floor], key=by_rank)) or "(nothing)"}')
    print('per top-level folder:')
    print(f'  {"folder":10s} {"files":>5s} {"lines":>6s} {"modules":>7s} {"cycles":>6s} {"upward":>6s}  includes')
    for top, f in folder_figures(graph, lines, found, upward).items():
        print(f'  {top:10s} {f["files"]:5d} {f["lines"]:6d} {f["modules"]:7d} {f["cycles"]:6d} {f["upward"]:6d}  '
              f'{", ".join(f["includes"]) or "(nothing)"}')
    print(f'cycles: {len(found)} ({len(known)} known, listed in KNOWN_CYCLES)')
    for component in found:
        print('  ' + ' <-> '.join(map(name, component)) + ('  (known)' if component in known else ''))
    print(f'upward includes: {len(upward)}')
    for a, b in upward:
        print(f'  {name(a)} -> {name(b)}')
    print(f'folders without a place: {len(homeless)}')
    for folder in homeless:
        print(f'  {folder}/')
    code = {p: n for p, n in lines.items() if rank(module_of(p)[0]) is not None and module_of(p)[0] not in LEAVES}
    leaves = {p: n for p, n in lines.items() if p not in code}
    for title, group in (('largest files (floors)', code), ('largest files (leaves: tests, benchmarks, fuzz, examples)', leaves)):
        print(title + ':')
        for path, count in sorted(group.items(), key=lambda item: (-item[1], item[0]))[:5]:
            print(f'  {count:5d} {path}')
    for title, group in (('longest functions (floors)', code), ('longest functions (leaves)', leaves)):
        print(title + ':')
        for count, where in longest_functions(root, group, 5):
            print(f'  {count:5d} {where}')


if __name__ == '__main__':
    main()
