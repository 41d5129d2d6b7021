#!/usr/bin/env python3
"""Every repository path the documentation cites exists.

usage: cited_paths.py REPO_ROOT

Scans README.md, docs/**/*.md, benchmarks/RESULTS.md and benchmarks/results/*.md for paths in
inline code (`...`), in fenced code blocks and in markdown links, and prints FILE:LINE: PATH for
each one that names nothing in the tree; exit 1 if any, 0 otherwise. A word counts as a
repository path when its first component is a top-level entry of the tree (benchmarks/, docs/,
scripts/, src/, ...) or when it looks like a root document (README.md, RESULTS.md); other
words (`trajectory.h5`, `DIR/summary.json`, `emergent/kit/capsomer.hpp`) are file names in
another frame and are left alone. Globs and brace lists (`benchmarks/logs/phenomena/
taylor-couette_seed*/`, `figures/x-{a,b}.png`) must match at least one path. Markdown link
targets are relative to the file that holds them, as a reader's viewer resolves them.
"""
import glob
import os
import re
import sys

# Paths under a run's output directory (out/...) and the build tree (build/...) are what a
# command writes, not tracked files: they cannot be checked against the tree, so they are skipped.
SKIPPED_PREFIXES = ("out/", "build/")
# Words that are never paths even when they start like one: placeholders (<name>, $OUT, a
# component in capitals without an extension: SCENE[_seedS], DIR) and elisions (...).
PLACEHOLDER = re.compile(r"[<>]|\.\.\.|\$|(^|/)[A-Z][A-Z_]*(\[[^/]*\])?(/|$)")
ROOT_DOCUMENT = re.compile(r"^[A-Z][A-Za-z_]*\.(md|txt)$")
TRAILING = ",;:.)('\"`"


def documents(root):
    found = ["README.md", "benchmarks/RESULTS.md"]
    found += sorted(glob.glob("docs/**/*.md", root_dir=root, recursive=True))
    found += sorted(glob.glob("benchmarks/results/*.md", root_dir=root))
    return [p for p in found if os.path.isfile(os.path.join(root, p))]


def expand_braces(word):
    """a{b,c}d -> [abd, acd], repeatedly; no nesting is needed by the documents."""
    m = re.search(r"\{([^{}]*,[^{}]*)\}", word)
    if not m:
        return [word]
    out = []
    for part in m.group(1).split(","):
        out += expand_braces(word[:m.start()] + part + word[m.end():])
    return out


def exists(base, path, argument=False):
    """argument: a command's later word, which may be an output prefix: `scripts/plot_x DIR
    benchmarks/figures/x-small` writes benchmarks/figures/x-small-*.png."""
    if argument and glob.glob(os.path.normpath(os.path.join(base, path)) + "*"):
        return True
    for one in expand_braces(path):
        full = os.path.normpath(os.path.join(base, one))
        if any(c in one for c in "*?["):
            if not glob.glob(full):
                return False
        elif not os.path.exists(full):
            return False
    return True


def repository_path(word, top_level):
    word = word.strip(TRAILING)
    if word.startswith("./"):
        word = word[2:]
    if not word or PLACEHOLDER.search(word) or word.startswith(SKIPPED_PREFIXES):
        return None
    first = word.split("/", 1)[0]
    if "/" in word and first in top_level:
        return word
    if "/" not in word and (ROOT_DOCUMENT.match(word) or (first in top_level and "." in first)):
        return word
    return None


def check(root, doc, top_level):
    text = open(os.path.join(root, doc), encoding="utf-8").read()
    lines = text.split("\n")
    cited = []  # (line, path, base directory, a command's later word)
    # Fenced blocks first: every word of every line; then blank them so that their backticks
    # do not pair with inline ones.
    fenced, plain = False, []
    for number, line in enumerate(lines, 1):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            plain.append("")
            continue
        if fenced:
            for i, word in enumerate(re.split(r"[\s=\"']+", line.split(" #", 1)[0].strip())):
                path = repository_path(word, top_level)
                if path:
                    cited.append((number, path, root, i > 0))
            plain.append("")
        else:
            plain.append(line)
    body = "\n".join(plain)
    line_of = lambda offset: body.count("\n", 0, offset) + 1
    # Inline code may wrap across line breaks, never across a paragraph.
    for m in re.finditer(r"`([^`]+?)`", body):
        if "\n\n" in m.group(1):
            continue
        # A path wrapped after a "/" or "-" is one word again.
        span = re.sub(r"([/-])\n\s*", r"\1", m.group(1))
        for i, word in enumerate(span.split()):
            path = repository_path(word, top_level)
            if path:
                cited.append((line_of(m.start()), path, root, i > 0))
    for m in re.finditer(r"!?\[[^\]]*\]\(([^)\s]+)\)", body):
        target = m.group(1).split("#", 1)[0]
        if not target or re.match(r"^[a-z]+:", target):  # an anchor alone, http:, mailto:
            continue
        cited.append((line_of(m.start()), target, os.path.join(root, os.path.dirname(doc)), False))
    return len(cited), [(doc, n, p) for n, p, base, arg in cited if not exists(base, p, arg)]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.split("\n\n")[1])
    root = os.path.abspath(sys.argv[1])
    top_level = {e for e in os.listdir(root) if not e.startswith(".")} - {"build", "out"}
    docs = documents(root)
    missing, count = [], 0
    for doc in docs:
        n, lost = check(root, doc, top_level)
        count, missing = count + n, missing + lost
    for doc, number, path in missing:
        print(f"{doc}:{number}: {path} does not exist")
    print(f"cited_paths: {count} paths cited in {len(docs)} documents, {len(missing)} missing")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
