#!/usr/bin/python3
"""Checks the links of the user docs and the citations of docs in the tree.

1. Every markdown link [text](target) and image ![alt](target) in README.md,
   docs/*.md and bench/**/*.md whose target is not a URL names a file that
   exists (relative to the linking file), and its #anchor, if any, is the
   GitHub anchor of a heading of that file (lower case, punctuation other
   than '-' and '_' dropped, spaces to '-', repeats numbered -1, -2, ...).
2. Every citation `docs/NAME.md` in code, tests, scripts, cases, bench and
   CI files names an existing page; a quoted section after it
   (docs/membrane.md, "Loads") is the start of a heading or of a bold
   paragraph lead (**Memory** ...) of that page, and so is an unquoted
   capitalised word after a comma (docs/homogenize-solver.md, Memory).
3. No user doc names a tracker issue ("issue 12", "#12"), in prose or in
   inline code (fenced code blocks are left alone).

Usage: check_links.py SOURCE_DIR. Prints one line per broken link and exits
1 if there is any, else prints a count and exits 0.
check_links.py --self-test plants a broken file link, a bad anchor, a bad
citation and a tracker issue in a temporary tree and exits 1 unless each
is reported (and nothing else is). Standard library only.
"""
import os
import re
import sys
import tempfile

LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
BOLD_LEAD = re.compile(r"^\*\*([^*]+)\*\*")
CITATION = re.compile(r"docs/([A-Za-z0-9_.-]+\.md)(?:,?\s*(?:\"([^\"\n]*)\"?|'([^'\n]*)'?|([A-Z][A-Za-z-]*)))?")
ISSUE = re.compile(r"\b[Ii]ssues? #?\d+|(?<![\w&/])#\d+\b")
CODE_DIRS = ["core", "materials", "micro", "homogenize", "membrane", "tests",
             "scripts", "bench", "cases", "fuzz", ".ci"]
CODE_FILES = ["Makefile", "CMakeLists.txt"]


def strip_code(lines, keep_inline=False):
    """Yields (number, line) outside fenced code blocks; inline code blanked
    unless keep_inline (a heading's anchor keeps the text of its code)."""
    fence = None
    for number, line in enumerate(lines, 1):
        stripped = line.lstrip()
        if fence:
            if stripped.startswith(fence):
                fence = None
            continue
        if stripped.startswith("```") or stripped.startswith("~~~"):
            fence = stripped[:3]
            continue
        yield number, line if keep_inline else re.sub(r"`[^`]*`", "``", line)


def anchor(text):
    """GitHub's anchor of a heading text."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links keep their text
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def plain(text):
    """A heading or citation without markdown emphasis, code ticks, case."""
    return re.sub(r"[`*_]", "", text).strip().lower()


class Page:
    def __init__(self, path):
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        self.anchors = set()
        self.sections = []
        seen = {}
        for _, line in strip_code(lines, keep_inline=True):
            m = HEADING.match(line)
            if m:
                a = anchor(m.group(2))
                n = seen.get(a, 0)
                seen[a] = n + 1
                self.anchors.add(a if n == 0 else f"{a}-{n}")
                self.sections.append(plain(m.group(2)))
                continue
            m = BOLD_LEAD.match(line)
            if m:
                self.sections.append(plain(m.group(1)))

    def has_section(self, name):
        name = plain(name).rstrip(".,;:)")
        return bool(name) and any(s.startswith(name) for s in self.sections)


def user_docs(root):
    paths = [os.path.join(root, "README.md")]
    docs = os.path.join(root, "docs")
    paths += sorted(os.path.join(docs, f) for f in os.listdir(docs) if f.endswith(".md"))
    return paths


def bench_notes(root):
    found = []
    for folder, _, files in os.walk(os.path.join(root, "bench")):
        found += [os.path.join(folder, f) for f in files if f.endswith(".md")]
    return sorted(found)


def check(root):
    """Returns (errors, count of links and citations checked) for a tree."""
    pages = {}
    errors = []
    checked = 0

    def page(path):
        if path not in pages:
            pages[path] = Page(path)
        return pages[path]

    def rel(path):
        return os.path.relpath(path, root)

    docs = user_docs(root)
    for path in docs + bench_notes(root):
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        for number, raw in strip_code(lines, keep_inline=True):
            if path in docs:
                for m in ISSUE.finditer(raw):
                    errors.append(f"{rel(path)}:{number}: names a tracker issue: '{m.group(0)}'")
            line = re.sub(r"`[^`]*`", "``", raw)  # no links inside inline code
            for m in LINK.finditer(line):
                target = m.group(1)
                if re.match(r"^[a-z]+:", target):
                    continue
                checked += 1
                file_part, _, frag = target.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                where = f"{rel(path)}:{number}: ({target})"
                if not os.path.exists(dest):
                    errors.append(f"{where}: no file {rel(dest)}")
                    continue
                if frag:
                    if not dest.endswith(".md"):
                        errors.append(f"{where}: an anchor into a file that is not markdown")
                    elif frag not in page(dest).anchors:
                        errors.append(f"{where}: no heading with anchor #{frag} in {rel(dest)}")

    sources = [os.path.join(root, f) for f in CODE_FILES]
    for d in CODE_DIRS:
        for folder, _, files in os.walk(os.path.join(root, d)):
            sources += [os.path.join(folder, f) for f in files]
    for path in sorted(sources):
        if not os.path.isfile(path) or path.endswith(".md") or path == os.path.abspath(__file__):
            continue
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except (UnicodeDecodeError, OSError):
            continue
        for number, line in enumerate(text.split("\n"), 1):
            for m in CITATION.finditer(line):
                if line[:m.start()].endswith("/") and not line[:m.start()].endswith(" /"):
                    continue  # a path that only ends in docs/ (docs/images/...)
                checked += 1
                dest = os.path.join(root, "docs", m.group(1))
                where = f"{rel(path)}:{number}: docs/{m.group(1)}"
                if not os.path.exists(dest):
                    errors.append(f"{where}: no such page")
                    continue
                section = m.group(2) or m.group(3) or m.group(4)
                if section and not page(dest).has_section(section):
                    errors.append(f"{where}: no section '{section.strip()}'")

    return errors, checked


PLANTED = {
    "README.md": "# Tree\n\nSee [the guide](docs/guide.md#usage) and [gone](docs/missing.md).\n",
    "docs/guide.md": "# Guide\n\n## Usage\n\n**Memory** is bounded.\n\n"
                     "Back to [the readme](../README.md#tree) and [nowhere](#no-such-heading).\n\n"
                     "Fixed in `issue 12`.\n",
    "scripts/tool.sh": "# see docs/guide.md, \"Usage\" and docs/guide.md, Memory\n"
                       "# and docs/guide.md, \"No Such Section\"\n",
}
EXPECTED = [
    "README.md:3: (docs/missing.md): no file docs/missing.md",
    "docs/guide.md:7: (#no-such-heading): no heading with anchor #no-such-heading",
    "scripts/tool.sh:2: docs/guide.md: no section 'No Such Section'",
    "docs/guide.md:9: names a tracker issue: 'issue 12'",
]


def self_test():
    """Plants one fault of each kind (and correct links beside them) in a
    temporary tree; fails unless each fault is reported and nothing else."""
    with tempfile.TemporaryDirectory() as root:
        for name, text in PLANTED.items():
            os.makedirs(os.path.join(root, os.path.dirname(name)), exist_ok=True)
            with open(os.path.join(root, name), "w", encoding="utf-8") as f:
                f.write(text)
        errors, _ = check(root)
    return compare_planted(errors, EXPECTED)


def compare_planted(errors, expected):
    """A self-test's verdict (also readme_commands.py's): prints each planted
    fault (the start of its message) not reported and each report not
    planted; 1 if there is any, else 0."""
    missed = [e for e in expected if not any(found.startswith(e) for found in errors)]
    extra = [e for e in errors if not any(e.startswith(x) for x in expected)]
    for e in missed:
        print(f"self-test: the planted fault was not reported: {e}")
    for e in extra:
        print(f"self-test: reported, but not planted: {e}")
    if missed or extra:
        return 1
    print(f"self-test: all {len(expected)} planted faults reported, nothing else")
    return 0


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--self-test":
        return self_test()
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    errors, checked = check(root)
    for e in errors:
        print(e)
    if errors:
        print(f"{len(errors)} broken of {checked} links and citations")
        return 1
    print(f"{checked} links and citations checked, none broken")
    return 0


if __name__ == "__main__":
    sys.exit(main())
