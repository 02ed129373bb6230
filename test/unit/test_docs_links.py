"""Every relative link and #anchor in README.md, BENCHMARKS.md and docs/*.md resolves: the file
exists and the anchor is one of its headings' slugs as GitHub makes them."""

import glob
import os
import re
from typing import Dict, List, Set, Tuple

import pytest

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PAGES = sorted(
    [os.path.join(REPO_ROOT, 'README.md'), os.path.join(REPO_ROOT, 'BENCHMARKS.md')]
    + glob.glob(os.path.join(REPO_ROOT, 'docs', '*.md'))
)

FENCE = re.compile(r'^\s*(```|~~~)')
HEADING = re.compile(r'^ {0,3}(#{1,6})\s+(.*?)\s*#*\s*$')
INLINE_CODE = re.compile(r'`[^`]*`')
LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')
EXTERNAL = re.compile(r'^[a-zA-Z][a-zA-Z0-9+.-]*:')  # http:, https:, mailto:, ...


def prose_lines(text: str) -> List[Tuple[int, str]]:
    """(line number, line) outside fenced code blocks."""
    lines, fenced = [], False
    for number, line in enumerate(text.split('\n'), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            lines.append((number, line))
    return lines


def slug(heading: str) -> str:
    """GitHub's anchor for a heading: markup dropped, lower case, punctuation other than '-'
    and '_' removed, each space a '-'."""
    text = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', heading)  # a link's text only
    text = re.sub(r'<[^>]+>', '', text)  # inline HTML
    return re.sub(r'[^\w\- ]', '', text.lower()).replace(' ', '-')


def anchors(path: str) -> Set[str]:
    """Every heading anchor of a markdown file, with GitHub's -1, -2 for repeats."""
    with open(path, encoding='utf-8') as f:
        text = f.read()
    seen: Dict[str, int] = {}
    found = set()
    for _, line in prose_lines(text):
        match = HEADING.match(line)
        if not match:
            continue
        base = slug(match.group(2))
        count = seen.get(base, 0)
        seen[base] = count + 1
        found.add(base if count == 0 else '%s-%d' % (base, count))
    return found


def links(path: str) -> List[Tuple[int, str]]:
    """(line number, target) of every relative link of a markdown file, code left out."""
    with open(path, encoding='utf-8') as f:
        text = f.read()
    found = []
    for number, line in prose_lines(text):
        for match in LINK.finditer(INLINE_CODE.sub('', line)):
            target = match.group(1)
            if not EXTERNAL.match(target):
                found.append((number, target))
    return found


def broken_links(page: str) -> List[str]:
    """What is wrong with a page's links, one line each naming the line and the target."""
    problems = []
    for number, target in links(page):
        where = '%s:%d: %s' % (os.path.relpath(page, REPO_ROOT), number, target)
        file_part, _, anchor = target.partition('#')
        linked = page
        if file_part:
            linked = os.path.normpath(os.path.join(os.path.dirname(page), file_part))
        if not os.path.exists(linked):
            problems.append('%s: no file %s' % (where, os.path.relpath(linked, REPO_ROOT)))
        elif anchor and linked.endswith('.md') and anchor not in anchors(linked):
            problems.append('%s: no heading with anchor #%s' % (where, anchor))
    return problems


def test_slugs_are_githubs():
    assert slug("Tuning: does the seed's arm shake?") == 'tuning-does-the-seeds-arm-shake'
    assert slug('Long runs: `make soak`') == 'long-runs-make-soak'
    assert slug('Trajectories (the MoveIt path)') == 'trajectories-the-moveit-path'
    assert slug("Timing, as Gazebo's: physics waits") == 'timing-as-gazebos-physics-waits'
    assert slug('[BENCHMARKS](BENCHMARKS.md) and more_x') == 'benchmarks-and-more_x'


def test_the_checker_finds_broken_links(tmp_path):
    page = tmp_path / 'page.md'
    (tmp_path / 'other.md').write_text('# Other page\n\n## A part\n\n```\n# not a heading\n```\n')
    page.write_text(
        '# Page\n\n[ok](other.md#a-part) [self](#page) [web](https://example.com/x#y)\n'
        '[gone](missing.md) [bad anchor](other.md#not-a-heading) `[code](nowhere.md)`\n'
        '```\n[fenced](nowhere.md)\n```\n'
    )
    problems = broken_links(str(page))
    assert len(problems) == 2, problems
    assert 'no file' in problems[0] and 'missing.md' in problems[0]
    assert 'no heading with anchor #not-a-heading' in problems[1]


def test_readme_and_docs_exist():
    assert os.path.join(REPO_ROOT, 'README.md') in PAGES
    assert len([p for p in PAGES if os.sep + 'docs' + os.sep in p]) >= 10


@pytest.mark.parametrize('page', PAGES, ids=lambda p: os.path.relpath(p, REPO_ROOT))
def test_every_link_resolves(page):
    assert broken_links(page) == []


def test_readme_is_short():
    with open(os.path.join(REPO_ROOT, 'README.md'), encoding='utf-8') as f:
        assert len(f.read().split('\n')) <= 250
