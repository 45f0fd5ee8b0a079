#!/usr/bin/env python3
"""The library's include graph: its wings, the modules in each, cycles and upward includes.

    python3 scripts/include_graph.py [ROOT]          # print the graph and the figures
    python3 scripts/include_graph.py --check [ROOT]  # exit 1 on a cycle or an upward include

A module is a source file and its header (generator/<wing>/<name>.cpp with
generator/include/saagen/<wing>/<name>.hpp); its wing is the folder. The wings are ordered,
lowest first (WINGS): a module may include its own wing and the wings below it, never one above,
and no two modules may include each other through any chain. cli/ and report/ sit above every
wing and are checked for cycles only. ctest runs the check (tests/CMakeLists.txt).
"""
import collections
import os
import re
import sys

WINGS = ['base', 'io', 'front', 'target', 'print', 'emit', 'validate', 'products', 'scene', 'integrate']
TOOLS = ['report', 'cli']
INCLUDE = re.compile(r'^\s*#\s*include\s+[<"]([^>"]+)[>"]', re.M)
LITERAL = re.compile(r'R"\((?:.|\n)*?\)"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])\'')  # raw, string and char literals
FUNCTION = re.compile(r'^[A-Za-z][^;{}()]*\b(\w+)\([^;]*\)\s*(const\s*)?(->[^{;]*)?\{\s*$', re.M)


def module_of(path):
    """(wing, name) of a library or tool file, relative to the repository root."""
    parts = path.split('/')
    name = os.path.splitext(parts[-1])[0]
    if parts[0] == 'generator':
        if parts[1] == 'include':
            return ('base', name) if len(parts) == 4 else (parts[3], name)
        return parts[1], name
    return parts[0], name


def source_files(root):
    for top in ['generator'] + TOOLS:
        for folder, _, names in os.walk(os.path.join(root, top)):
            for name in sorted(names):
                if name.endswith(('.cpp', '.hpp', '.h')):
                    yield os.path.relpath(os.path.join(folder, name), root)


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
        if path.endswith('.cpp'):
            sources[module_of(path)[1]].add(module_of(path))
    def namer(path):
        module = module_of(path)
        if module[0] == 'base' and len(sources.get(module[1], ())) == 1:
            return next(iter(sources[module[1]]))
        return module
    return namer


def module_graph(root):
    files = list(source_files(root))
    index = header_index(files)
    module_of = module_namer(files)
    graph = collections.defaultdict(set)
    lines = {}
    for path in files:
        text = open(os.path.join(root, path), encoding='utf-8').read()
        lines[path] = text.count('\n')
        source = module_of(path)
        graph[source]
        for spelled in INCLUDE.findall(text):
            target = index.get(spelled)
            if target is None:
                local = os.path.normpath(os.path.join(os.path.dirname(path), spelled))
                target = local if local in lines or os.path.exists(os.path.join(root, local)) else None
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


def rank(wing):
    if wing in WINGS:
        return WINGS.index(wing)
    if wing in TOOLS:
        return len(WINGS) + TOOLS.index(wing)
    return -1  # the flat layout before the wings: every module in one folder


def upward_includes(graph):
    return sorted((a, b) for a, targets in graph.items() for b in targets
                  if rank(a[0]) >= 0 and rank(b[0]) > rank(a[0]) and a[0] not in TOOLS)


def longest_functions(root, files, count):
    sizes = []
    for path in files:
        if not path.endswith('.cpp'):
            continue
        text = LITERAL.sub('""', open(os.path.join(root, path), encoding='utf-8').read())
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


def main():
    arguments = [a for a in sys.argv[1:] if a != '--check']
    root = arguments[0] if arguments else os.path.join(os.path.dirname(__file__), '..')
    graph, lines = module_graph(root)
    found, upward = cycles(graph), upward_includes(graph)
    if '--check' in sys.argv:
        for component in found:
            print('include cycle: ' + ' <-> '.join(map(name, component)))
        for a, b in upward:
            print(f'upward include: {name(a)} includes {name(b)} (wing order, lowest first: {", ".join(WINGS)})')
        sys.exit(1 if found or upward else 0)
    per_folder = collections.Counter(os.path.dirname(p) for p in lines)
    print('files per folder:')
    for folder, count in sorted(per_folder.items()):
        print(f'  {folder:40s} {count:3d} files {sum(n for p, n in lines.items() if os.path.dirname(p) == folder):6d} lines')
    print('wing dependencies:')
    wing_edges = collections.defaultdict(set)
    for a, targets in graph.items():
        for b in targets:
            if a[0] != b[0]:
                wing_edges[a[0]].add(b[0])
    for wing in sorted(wing_edges, key=rank):
        print(f'  {wing:10s} -> {", ".join(sorted(wing_edges[wing], key=rank))}')
    print(f'cycles: {len(found)}')
    for component in found:
        print('  ' + ' <-> '.join(map(name, component)))
    print(f'upward includes: {len(upward)}')
    for a, b in upward:
        print(f'  {name(a)} -> {name(b)}')
    print('largest files:')
    for path, count in sorted(lines.items(), key=lambda item: -item[1])[:5]:
        print(f'  {count:5d} {path}')
    print('longest functions:')
    for count, where in longest_functions(root, lines, 5):
        print(f'  {count:5d} {where}')


if __name__ == '__main__':
    main()
