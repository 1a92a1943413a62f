#!/usr/bin/env python3
"""Checks of the documentation that a test can make.

  check_docs.py links ROOT FILE.md...   every relative link and image of each file names a file
                                        that exists, and a #fragment a heading of its target
                                        (GitHub's anchors); links in code are not links
  check_docs.py excerpt ROOT README.md SOURCE
                                        every ```cpp block of README.md is a verbatim part of
                                        SOURCE (the code a test compiles)
  check_docs.py length ROOT FILE.md N   FILE.md has at most N lines

Prints one line per fault and exits 1 when there is one, else prints "ok" and exits 0.
"""
import os
import re
import sys

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(([^()\s]+)\)")
INLINE_CODE = re.compile(r"(`+)(?:(?!\1).)+\1")
FENCE = re.compile(r"^\s*(```|~~~)")


def prose_lines(text):
    """(line number, line) outside fenced code blocks."""
    fenced = False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


def slug(heading):
    """GitHub's anchor of a heading: its text without markup, lower case, spaces to hyphens,
    every character but letters, digits, '-' and '_' left out."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link's text
    text = text.replace("`", "").replace("*", "")
    text = text.strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def anchors(path):
    found = set()
    seen = {}
    with open(path, encoding="utf-8") as f:
        for _, line in prose_lines(f.read()):
            m = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
            if not m:
                continue
            base = slug(m.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            found.add(base if count == 0 else f"{base}-{count}")
    return found


def check_links(root, files):
    faults = []
    for name in files:
        path = os.path.join(root, name)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for number, line in prose_lines(text):
            for m in LINK.finditer(INLINE_CODE.sub("", line)):
                target = m.group(1)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                    continue
                file_part, _, fragment = target.partition("#")
                resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                where = f"{name}:{number}: {target}"
                if not os.path.exists(resolved):
                    faults.append(f"{where}: no such file {os.path.relpath(resolved, root)}")
                elif fragment and resolved.endswith(".md") and fragment not in anchors(resolved):
                    faults.append(f"{where}: no heading #{fragment} in {os.path.relpath(resolved, root)}")
    return faults


def check_excerpt(root, readme, source):
    with open(os.path.join(root, readme), encoding="utf-8") as f:
        text = f.read()
    with open(os.path.join(root, source), encoding="utf-8") as f:
        code = f.read()
    blocks = re.findall(r"^```cpp\n(.*?)^```", text, re.S | re.M)
    if not blocks:
        return [f"{readme}: no ```cpp block"]
    return [f"{readme}: ```cpp block {k + 1} is not a verbatim part of {source}"
            for k, block in enumerate(blocks) if block not in code]


def check_length(root, name, most):
    with open(os.path.join(root, name), encoding="utf-8") as f:
        lines = len(f.read().splitlines())
    return [] if lines <= most else [f"{name}: {lines} lines, more than {most}"]


def main(argv):
    if len(argv) < 3 or argv[1] not in ("links", "excerpt", "length"):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    mode, root, rest = argv[1], argv[2], argv[3:]
    if mode == "links":
        faults = check_links(root, rest)
    elif mode == "excerpt":
        faults = check_excerpt(root, *rest)
    else:
        faults = check_length(root, rest[0], int(rest[1]))
    for fault in faults:
        print(fault)
    if faults:
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
