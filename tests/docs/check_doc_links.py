#!/usr/bin/env python3
"""Every relative link and image in README.md and docs/*.md points at a file
that exists, and every #anchor at a heading of that file (GitHub's slugs).
Usage: check_doc_links.py REPO_ROOT. Exit 1 listing each broken link."""
import pathlib
import re
import sys

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
FENCE = re.compile(r"^(```|~~~)")


def prose_lines(text):
    """The lines outside fenced code blocks, where a ](...) is not a link."""
    inside = False
    for line in text.splitlines():
        if FENCE.match(line.lstrip()):
            inside = not inside
            continue
        if not inside:
            yield line


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"[`*_]", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    found = set()
    for line in prose_lines(path.read_text(encoding="utf-8")):
        match = re.match(r"^#{1,6}\s+(.*)$", line)
        if match:
            found.add(slug(match.group(1)))
    return found


def broken_links(page, root):
    for number, line in enumerate(prose_lines(page.read_text(encoding="utf-8")), 1):
        for target in LINK.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:, file:
                continue
            file_part, _, anchor = target.partition("#")
            resolved = (page.parent / file_part).resolve() if file_part else page.resolve()
            if not resolved.exists():
                yield f"{page.relative_to(root)}: {target}: no such file"
            elif anchor and resolved.suffix == ".md" and anchor not in anchors(resolved):
                yield f"{page.relative_to(root)}: {target}: no heading #{anchor} in {resolved.name}"


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    pages = [root / "README.md"] + sorted((root / "docs").glob("*.md"))
    problems = [problem for page in pages for problem in broken_links(page, root)]
    for problem in problems:
        print(problem)
    print(f"{len(pages)} pages checked, {len(problems)} broken links")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
