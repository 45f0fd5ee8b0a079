#!/usr/bin/env python3
"""Every link in the documentation resolves (ctest `doc_links`; a second, no build needed).

    python3 scripts/doc_links.py [ROOT]

Checks, in every Markdown file of the repository (README.md, docs/, examples/, the folders'
READMEs; node_modules and build folders left out):
- each Markdown link and image, `[text](target)` and `![alt](target)`, that is not a URL: the file
  or folder exists relative to the page, and a `#anchor` names a heading of the target page (as
  GitHub spells anchors: lower case, punctuation dropped, spaces to hyphens);
- in the front door and the pages that replaced its reference part (STRICT: README.md,
  docs/ARCHITECTURE.md, docs/CLI.md, docs/GUIDE.md, docs/SAFETY.md), also each repository path in
  backticks (`scripts/run.sh`, `docs/TAA.md`, `templates/*.saa`): it exists from the root, from the
  page's folder, or as an include spelling (`saagen/io/output.hpp` under a folder's include/).
"""
import glob
import os
import re
import subprocess
import sys

STRICT = ['README.md', 'docs/ARCHITECTURE.md', 'docs/CLI.md', 'docs/GUIDE.md', 'docs/SAFETY.md']
LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+"[^"]*")?\)')
CODE_SPAN = re.compile(r'`([^`\n]+)`')
FENCE = re.compile(r'^(```|~~~).*?^\1\s*$', re.M | re.S)
SKIPPED = ('node_modules', 'build', 'out', 'shared', '.')


def markdown_files(root):
    try:
        listed = subprocess.run(['git', '-C', root, 'ls-files', '--cached', '--others', '--exclude-standard', '*.md'],
                                capture_output=True, text=True, check=True).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        listed = [os.path.relpath(p, root) for p in glob.glob(os.path.join(root, '**', '*.md'), recursive=True)]
    return sorted(p for p in listed if not p.split('/')[0].startswith(SKIPPED) and '/node_modules/' not in p
                  and os.path.isfile(os.path.join(root, p)))


def slug(heading):
    """GitHub's anchor of a heading."""
    text = re.sub(r'`|\*\*|__|\[([^\]]*)\]\([^)]*\)', lambda m: m.group(1) or '', heading.strip().lower())
    text = re.sub(r'[^\w\- ]', '', text)
    return text.replace(' ', '-')


def anchors(path, cache={}):
    if path not in cache:
        text = FENCE.sub('', open(path, encoding='utf-8').read())
        found, seen = set(), {}
        for heading in re.findall(r'^#{1,6}\s+(.*?)\s*#*\s*$', text, re.M):
            base = slug(heading)
            count = seen.get(base, 0)
            found.add(base if count == 0 else f'{base}-{count}')
            seen[base] = count + 1
        found |= set(re.findall(r'<a (?:name|id)="([^"]+)"', text))
        cache[path] = found
    return cache[path]


def path_exists(root, page, token):
    folder = os.path.dirname(os.path.join(root, page))
    candidates = [os.path.join(root, token), os.path.join(folder, token)]
    if token.startswith('saagen/'):
        candidates += glob.glob(os.path.join(root, '*', 'include', token))
    return any(glob.glob(c) if any(ch in c for ch in '*?[') else os.path.exists(c) for c in candidates)


def looks_like_path(root, token, tops):
    if ' ' in token or '<' in token or token.startswith(('-', '/', 'http')) or '://' in token:
        return False
    first = token.split('/')[0]
    return '/' in token and (first in tops or first == 'saagen') and re.search(r'(\.[A-Za-z0-9]+|/)$', token) is not None


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..')
    tops = {name for name in os.listdir(root) if os.path.isdir(os.path.join(root, name)) and not name.startswith('.')}
    problems, links, paths = [], 0, 0
    pages = markdown_files(root)
    for page in pages:
        text = open(os.path.join(root, page), encoding='utf-8').read()
        prose = FENCE.sub('', text)
        for target in LINK.findall(prose):
            if re.match(r'[a-z][a-z0-9+.-]*:', target):  # https:, mailto:
                continue
            links += 1
            file_part, _, anchor = target.partition('#')
            resolved = os.path.normpath(os.path.join(os.path.dirname(os.path.join(root, page)), file_part)) if file_part \
                else os.path.join(root, page)
            if not os.path.exists(resolved):
                problems.append(f'{page}: link to {target}: no such file')
            elif anchor and resolved.endswith('.md') and anchor not in anchors(resolved):
                problems.append(f'{page}: link to {target}: no heading with that anchor in {os.path.relpath(resolved, root)}')
        if page in STRICT:
            for span in CODE_SPAN.findall(prose):
                token = span.strip().rstrip('.,;:')
                token = re.sub(r'[?#].*$', '', token)
                token = re.sub(r':\d+$', '', token)
                if looks_like_path(root, token, tops):
                    paths += 1
                    if not path_exists(root, page, token):
                        problems.append(f'{page}: `{span}`: no such path')
    for problem in problems:
        print('doc_links: ' + problem)
    print(f'doc_links: {len(pages)} pages, {links} links and {paths} paths checked, {len(problems)} broken')
    sys.exit(1 if problems else 0)


if __name__ == '__main__':
    main()
