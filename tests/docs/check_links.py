#!/usr/bin/env python3
"""Checks that the documents a reader gets with nimbus hold together (CTest: Docs.LinksResolve).

    python3 tests/docs/check_links.py [REPO_ROOT]

Every Markdown file of the repository (tracked, or new and not ignored by git; build folders
excluded) is read, and each link and image in it must resolve inside the repository:

- a relative path must name a file or folder that exists, and must not leave the repository
  root (a leading '/' is the repository root, as on GitHub);
- an anchor (`file.md#heading` or `#heading`) must be the slug of a heading of that file, by
  GitHub's rule: lower case, everything but letters, digits, '_', '-' and spaces dropped, spaces
  made '-', a repeated heading gets '-1', '-2', ... (or an HTML `id`/`name` in the file);
- http(s) and mailto links are allowed and not fetched.

Documents must not point at notes that are not shipped: no `../shared` and no `research-*.md`
anywhere in a Markdown file. README.md and docs/ are the user's documents: they must also not
name issues ("issue 15") or seed documents by number ("seed 004"), which a reader cannot open.

Links are read from inline links and images `[text](target)`, reference definitions
`[label]: target`, and HTML `src="..."` / `href="..."`; code spans and fenced code are skipped.
Exits 0 when everything resolves, 1 with one line per problem otherwise.
"""
import os
import re
import subprocess
import sys
import unicodedata
from urllib.parse import unquote

BUILD_DIR = re.compile(r"^(build[^/]*|out|\.git|\.gl|\.whl)/")
FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})")
HEADING_ATX = re.compile(r"^ {0,3}(#{1,6})[ \t]+(.*?)[ \t]*#*[ \t]*$")
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*(<[^>]*>|[^()\s]*(?:\([^()\s]*\)[^()\s]*)*)(?:\s+(?:\"[^\"]*\"|'[^']*'|\([^)]*\)))?\s*\)")
REF_DEF = re.compile(r"^ {0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")
HTML_ATTR = re.compile(r"""\b(?:src|href)\s*=\s*["']([^"']+)["']""", re.IGNORECASE)
HTML_ANCHOR = re.compile(r"""<a\s[^>]*\b(?:name|id)\s*=\s*["']([^"']+)["']""", re.IGNORECASE)
CODE_SPAN = re.compile(r"(`+)(.+?)\1")
EXTERNAL = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")
# Notes outside the repository, anywhere in any Markdown file.
OUTSIDE = re.compile(r"\.\./shared|research-[a-z-]+\.md")
# Names a reader of the user's documents cannot open.
UNOPENABLE = re.compile(r"[Ss]eeds? 0[0-9][0-9]|[Ii]ssues? #?[0-9]+")


def markdown_files(root):
    """Tracked and new, not ignored, Markdown files; every *.md on disk when git is unavailable."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                             check=True, capture_output=True).stdout.decode("utf-8", "surrogateescape")
        files = [f for f in out.split("\0") if f]
        files = [f for f in files if os.path.exists(os.path.join(root, f))]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for folder, dirs, names in os.walk(root):
            rel = os.path.relpath(folder, root)
            rel = "" if rel == "." else rel.replace(os.sep, "/") + "/"
            dirs[:] = [d for d in dirs if not BUILD_DIR.match(rel + d + "/")]
            files += [rel + n for n in names]
    return sorted(f for f in files if f.lower().endswith(".md") and not BUILD_DIR.match(f))


def slug(text):
    """GitHub's anchor for a heading's text."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links and images: their text
    text = re.sub(r"<[^>]+>", "", text)                       # inline HTML
    text = text.lower()
    # GitHub keeps word characters (letters, marks, decimal digits, connectors such as '_'),
    # spaces and hyphens.
    text = "".join(c for c in text
                   if c in " -" or unicodedata.category(c)[0] in "LM" or unicodedata.category(c) in ("Nd", "Pc"))
    return text.replace(" ", "-")


def scan(path):
    """(lines outside fenced code with their numbers, the set of anchors the file defines)."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    prose, anchors, counts = [], set(), {}
    fence = None
    for number, line in enumerate(lines, 1):
        m = FENCE.match(line)
        if fence:
            if m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence):
                fence = None
            continue
        if m:
            fence = m.group(1)
            continue
        prose.append((number, line))
        anchors.update(HTML_ANCHOR.findall(line))
        h = HEADING_ATX.match(line)
        heading = h.group(2) if h else None
        # Setext headings: a line of text underlined by === or ---.
        if not h and number < len(lines) and line.strip() and re.match(r"^ {0,3}(=+|-+)\s*$", lines[number]) \
                and not line.lstrip().startswith(("-", "*", "|", ">")):
            heading = line.strip()
        if heading is not None:
            base = slug(heading)
            n = counts.get(base, 0)
            anchors.add(base if n == 0 else f"{base}-{n}")
            counts[base] = n + 1
    return prose, anchors


def main():
    root = os.path.realpath(sys.argv[1] if len(sys.argv) > 1 else
                            os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    files = markdown_files(root)
    if not files:
        print(f"check_links: no Markdown files under {root}")
        return 1
    cache = {}

    def anchors_of(rel):
        if rel not in cache:
            cache[rel] = scan(os.path.join(root, rel))[1]
        return cache[rel]

    problems, links = [], 0
    for rel in files:
        prose, _ = scan(os.path.join(root, rel))
        with open(os.path.join(root, rel), encoding="utf-8") as f:
            lines = f.read().split("\n")
        user_doc = rel == "README.md" or rel.startswith("docs/")
        here = os.path.dirname(rel)
        for number, line in prose:
            where = f"{rel}:{number}"
            for m in OUTSIDE.finditer(line):
                problems.append(f"{where}: names a note outside the repository: '{m.group(0)}'")
            if user_doc:
                for m in UNOPENABLE.finditer(line):
                    problems.append(f"{where}: names what a reader cannot open: '{m.group(0)}' "
                                    "(say what it meant, or cite the published source in docs/references.md)")
            text = CODE_SPAN.sub(lambda s: " " * len(s.group(0)), line)
            targets = [m.group(1) for m in INLINE_LINK.finditer(text)]
            m = REF_DEF.match(text)
            if m and (number == 1 or not lines[number - 2].strip()):  # a definition starts a paragraph
                targets.append(m.group(1))
            targets += HTML_ATTR.findall(text)
            for target in targets:
                links += 1
                target = target.strip("<>")
                if EXTERNAL.match(target):
                    if not re.match(r"^(https?|mailto):", target, re.IGNORECASE):
                        problems.append(f"{where}: '{target}': only http(s) and mailto links may leave the repository")
                    continue
                path, _, anchor = target.partition("#")
                path = unquote(path.split("?", 1)[0])
                if path:
                    joined = path.lstrip("/") if path.startswith("/") else os.path.join(here, path)
                    full = os.path.realpath(os.path.join(root, joined))
                    if full != root and not full.startswith(root + os.sep):
                        problems.append(f"{where}: '{target}' leaves the repository")
                        continue
                    if not os.path.exists(full):
                        problems.append(f"{where}: '{target}': no such file in the repository")
                        continue
                    dest = os.path.relpath(full, root).replace(os.sep, "/")
                else:
                    dest = rel
                if anchor:
                    if not dest.lower().endswith(".md") or os.path.isdir(os.path.join(root, dest)):
                        continue  # line anchors of source files (#L10) are GitHub's, not a heading's
                    if unquote(anchor).lower() not in anchors_of(dest):
                        problems.append(f"{where}: '{target}': {dest} has no heading with the anchor #{anchor}")
    for p in problems:
        print(p)
    print(f"check_links: {len(files)} Markdown files, {links} links, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
