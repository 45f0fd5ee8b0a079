#!/usr/bin/env python3
"""docs/CLI.md against the command line's own help (ctest `cli_doc`).

    python3 scripts/cli_doc_check.py SAAGEN [DOC]           # exit 1 when DOC and the help disagree
    python3 scripts/cli_doc_check.py SAAGEN [DOC] --draft   # print a section skeleton per command

Walks `saagen --help` and every subcommand's `--help` (CLI11's "Subcommands:" lists), and checks
that DOC (default docs/CLI.md) has, for each command, a heading whose text is the command
(`## saagen emit`, `### saagen glints emit`), and that the first cell of that section's option
table names each of its options with every spelling (`` `-t`, `--target` ``) and each positional
(`` `FILE` ``). The reverse holds too: an option or positional in a table row that the help does
not list fails, so the page can neither miss an option nor keep a removed one. `-h,--help` is left
out (every command has it).
"""
import os
import re
import subprocess
import sys

ENTRY = re.compile(r'^  (\S.*?)(?:\s{2,}(\S.*))?$')


def help_text(saagen, path):
    result = subprocess.run([saagen] + path + ['--help'], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f'cli_doc_check: `saagen {" ".join(path + ["--help"])}` failed: {result.stderr.strip()}')
    return result.stdout


def parse(text):
    """{'description', 'positionals', 'options', 'subcommands'}: each entry (names, spec, description)."""
    lines = text.split('\n')
    parsed = {'description': '' if lines[0].startswith('Usage:') else lines[0].strip(), 'usage': '',
              'Positionals': [], 'Options': [], 'Subcommands': []}
    section, entry = None, None
    for line in lines[1:]:
        if line.startswith('Usage:'):
            parsed['usage'] = line[len('Usage:'):].strip()
        elif line.rstrip() in ('Positionals:', 'Options:', 'Subcommands:'):
            section, entry = line.rstrip()[:-1], None
        elif section and line.startswith('  ') and not line.startswith('    '):
            match = ENTRY.match(line.rstrip())
            spec, description = match.group(1), match.group(2) or ''
            if not description and len(line) > 30 and line[29] == ' ' and line[30] != ' ':
                spec, description = line[:29].strip(), line[30:].strip()  # a spec one space short of the column
            head = spec.split()[0]
            names = head.split(',') if section == 'Options' else [head]
            entry = [names, spec, description, line.strip()]
            parsed[section].append(entry)
        elif section and line.startswith('    ') and entry is not None:
            if entry[3] is not None:  # the description starts on the next line: the whole first line is the spec
                entry[1], entry[2], entry[3] = entry[3], '', None
            entry[2] = (entry[2] + ' ' + line.strip()).strip()
    return parsed


def commands(saagen, path=()):
    """(path, parsed help) of saagen and of every subcommand, depth first."""
    parsed = parse(help_text(saagen, list(path)))
    yield list(path), parsed
    for names, *_ in parsed['Subcommands']:
        yield from commands(saagen, tuple(path) + (names[0],))


def sections(doc):
    """Heading text -> the lines under it, up to the next heading of the same or a higher level."""
    found, lines = {}, doc.split('\n')
    heads = [(i, len(m.group(1)), m.group(2).strip().strip('`')) for i, line in enumerate(lines)
             for m in [re.match(r'^(#{1,6})\s+(.*)$', line)] if m]
    for k, (i, level, title) in enumerate(heads):
        end = next((j for j, lv, _ in heads[k + 1:] if lv <= level), len(lines))
        # a command's own section stops at its first sub-heading (a subcommand's section)
        sub = next((j for j, lv, _ in heads[k + 1:] if j < end), end)
        found[title] = lines[i + 1:sub]
    return found


def documented(section_lines):
    """Options (--x, -x) and positionals (UPPER) named in the first cell of the section's table rows."""
    names = set()
    for line in section_lines:
        cells = line.split('|')
        if not line.startswith('|') or len(cells) < 3 or set(cells[1].strip()) <= set('-: '):
            continue
        for token in re.findall(r'`([^`]+)`', cells[1]):
            token = token.split()[0].split('=')[0]
            if re.fullmatch(r'--?[A-Za-z0-9][A-Za-z0-9-]*|[A-Z][A-Z0-9_]*', token):
                names.add(token)
    return names


def draft(saagen):
    for path, parsed in commands(saagen):
        print('#' * min(2 + max(len(path) - 1, 0), 4) + ' saagen' + ''.join(' ' + p for p in path) + '\n')
        print(parsed['description'] + '\n')
        print('```\nsaagen' + parsed['usage'].split('saagen', 1)[-1] + '\n```\n')
        rows = [(e, 'positional') for e in parsed['Positionals']] + [(e, 'option') for e in parsed['Options'] if e[0][-1] != '--help']
        if rows:
            print('| option | value | meaning |\n|---|---|---|')
            for (names, spec, description, _), _ in rows:
                value = spec[len(spec.split()[0]):].strip()
                cell = lambda text: text.replace('|', '\\|')
                print(f'| {", ".join(f"`{n}`" for n in names)} | {cell(value)} | {cell(description)} |')
            print()


def main():
    arguments = [a for a in sys.argv[1:] if not a.startswith('--')]
    if not arguments:
        sys.exit(__doc__)
    saagen = arguments[0]
    doc_path = arguments[1] if len(arguments) > 1 else os.path.join(os.path.dirname(__file__), '..', 'docs', 'CLI.md')
    if '--draft' in sys.argv:
        draft(saagen)
        return
    doc = sections(open(doc_path, encoding='utf-8').read())
    problems, checked = [], 0
    for path, parsed in commands(saagen):
        command = 'saagen' + ''.join(' ' + p for p in path)
        if command not in doc:
            problems.append(f'no section "{command}" (a heading `## {command}`)')
            continue
        expected = {n for names, *_ in parsed['Options'] for n in names if n not in ('-h', '--help')}
        expected |= {names[0] for names, *_ in parsed['Positionals']}
        have = documented(doc[command])
        for name in sorted(expected - have):
            problems.append(f'{command}: `{name}` is in --help but not in the section\'s option table')
        for name in sorted(have - expected):
            problems.append(f'{command}: `{name}` is in the option table but not in --help')
        checked += 1
    for problem in problems:
        print(f'cli_doc_check: {os.path.relpath(doc_path)}: {problem}')
    print(f'cli_doc_check: {checked} commands checked against --help, {len(problems)} problems')
    sys.exit(1 if problems else 0)


if __name__ == '__main__':
    main()
