#!/usr/bin/env python3
"""Checks the user docs (README.md and every Markdown file under docs/) as a reader who cloned the
repository meets them: every relative link and image resolves to a file of the repository, and
every #anchor to a heading of its target; nothing names the project's shared folder outside the
repository (../shared) or a document it does not hold (a design brief, the papers' "seed" files,
issue numbers). Links in code blocks and code spans are not links and are left alone.

Usage: tests/docs_check.py [REPO_DIR]   (ctest runs it as DocsLinks); exits 1 listing each problem.
"""
import pathlib
import re
import sys
import urllib.parse

REPO = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent).resolve()

# [text](target) and ![alt](target), the target up to the first space or ')'; <img src="...">.
LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
IMG_SRC = re.compile(r"<img[^>]*\ssrc=\"([^\"]+)\"", re.I)
# Text a doc must not hold: outside paths and documents a clone does not have.
FORBIDDEN = [
    (re.compile(r"\.\./shared\b"), "names ../shared, which a clone of the repository does not have"),
    (re.compile(r"[D]ESIGN(\.md)?\s*(§|Sec)"), "cites a design brief outside the repository (cite docs/design.md)"),
    (re.compile(r"\bseed (Eq|0\d\d)"), "cites a seed file (cite the paper and its equation)"),
    (re.compile(r"\b[Ii]ssues? #?\d+"), "names an issue number (say what the thing is)"),
]


def docs():
    yield REPO / "README.md"
    yield from sorted((REPO / "docs").rglob("*.md"))


def prose(text):
    """The text with fenced code blocks and inline code spans blanked (line numbers kept)."""
    out, fence = [], None
    for line in text.split("\n"):
        stripped = line.lstrip()
        if fence is None and (stripped.startswith("```") or stripped.startswith("~~~")):
            fence = stripped[:3]
            out.append("")
            continue
        if fence is not None:
            if stripped.startswith(fence):
                fence = None
            out.append("")
            continue
        out.append(re.sub(r"`[^`]*`", lambda m: " " * len(m.group(0)), line))
    return out


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation but '-' and '_' dropped, spaces to '-'."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # links keep their text
    text = text.strip().lower().replace("`", "")
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        found, counts, fence = set(), {}, False
        for line in path.read_text(encoding="utf-8").split("\n"):
            if line.lstrip().startswith("```"):
                fence = not fence
            if fence:
                continue
            m = re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
            if m:
                base = slug(m.group(1))
                n = counts.get(base, 0)
                counts[base] = n + 1
                found.add(base if n == 0 else f"{base}-{n}")
            for a in re.findall(r"<a\s+(?:name|id)=\"([^\"]+)\"", line):
                found.add(a)
        cache[path] = found
    return cache[path]


def check(path):
    problems = []
    rel = path.relative_to(REPO)
    text = path.read_text(encoding="utf-8")
    for number, raw in enumerate(text.split("\n"), 1):
        for pattern, why in FORBIDDEN:  # code included: a command on ../shared is no use either
            if pattern.search(raw):
                problems.append(f"{rel}:{number}: {why}: {raw.strip()[:100]}")
    for number, line in enumerate(prose(text), 1):
        where = f"{rel}:{number}"
        for target in LINK.findall(line) + IMG_SRC.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto:
                continue
            file_part, _, anchor = target.partition("#")
            file_part = urllib.parse.unquote(file_part)
            dest = path if not file_part else (path.parent / file_part).resolve()
            if not dest.exists():
                problems.append(f"{where}: broken link {target} (no {file_part})")
                continue
            try:
                dest.relative_to(REPO)
            except ValueError:
                problems.append(f"{where}: link {target} leaves the repository")
                continue
            if anchor and dest.suffix == ".md" and urllib.parse.unquote(anchor) not in anchors(dest):
                problems.append(f"{where}: broken anchor {target} (no heading #{anchor} in {dest.relative_to(REPO)})")
    return problems


def main():
    problems = [p for path in docs() for p in check(path)]
    for p in problems:
        print(p)
    checked = sum(1 for _ in docs())
    print(f"{checked} files checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
