#!/usr/bin/env python3
"""Check that every relative Markdown link in README.md and docs/**/*.md resolves.

Usage: check_links.py [REPO_ROOT]   (default: two folders above this script)

For each file, every inline link target, [text](target) and ![alt](target), that is not
http(s):, mailto: or a pure #anchor must name a file or folder that exists, relative to the
linking file's own folder (a #fragment is stripped first). Paths written in `backticks` and
in fenced code blocks are not links and are not checked. Exits 1, listing each broken link as
FILE:LINE: target; 0 when every link resolves. Standard library only.
"""
import os
import re
import sys
from urllib.parse import unquote

# [text](target) or ![alt](target), with an optional "title"; the text may hold nested [..].
LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')
INLINE_CODE = re.compile(r'(`+)(?:(?!\1).)+?\1')
SKIP = re.compile(r'^(?:[a-zA-Z][a-zA-Z0-9+.-]*:|#)')  # any scheme (http:, https:, mailto:), #anchor


def markdown_files(root):
    readme = os.path.join(root, 'README.md')
    if os.path.isfile(readme):
        yield readme
    for folder, dirs, files in os.walk(os.path.join(root, 'docs')):
        dirs.sort()
        for name in sorted(files):
            if name.endswith('.md'):
                yield os.path.join(folder, name)


def broken_links(path):
    base = os.path.dirname(path)
    fence = None
    with open(path, encoding='utf-8') as f:
        for number, line in enumerate(f, 1):
            stripped = line.lstrip()
            marker = re.match(r'(`{3,}|~{3,})', stripped)
            if marker:
                if fence is None:
                    fence = marker.group(1)[0] * len(marker.group(1))
                elif stripped.startswith(fence):
                    fence = None
                continue
            if fence is not None:
                continue
            text = INLINE_CODE.sub('', line)
            for match in LINK.finditer(text):
                target = match.group(1)
                if SKIP.match(target):
                    continue
                target_path = unquote(target.split('#', 1)[0])
                if not target_path:
                    continue
                if not os.path.exists(os.path.join(base, target_path)):
                    yield number, target


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
    root = os.path.abspath(root)
    files = list(markdown_files(root))
    if not files:
        print(f'check_links: no README.md or docs/ under {root}', file=sys.stderr)
        return 1
    broken = []
    for path in files:
        for number, target in broken_links(path):
            broken.append(f'{os.path.relpath(path, root)}:{number}: {target}')
    if broken:
        print('\n'.join(broken))
        print(f'check_links: {len(broken)} broken relative link(s) in {len(files)} file(s)', file=sys.stderr)
        return 1
    print(f'check_links: every relative link resolves in {len(files)} file(s)')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
