#!/usr/bin/env python3
"""The layers stay straight: every include follows the table of docs/ARCHITECTURE.md.

The table under "## Layers" in docs/ARCHITECTURE.md is the one source of truth: each row names
a folder and the folders its files may include. This test reads every `#include "..."` of a
repository file in the C++ sources and checks

- that every source file lies in a folder of the table (a new folder needs its row),
- that every folder of the table exists,
- that an include of another folder's file is one its row allows,
- that no header includes itself again through other headers (an include cycle).

usage: layers_test.py SOURCE_DIR
"""
import os
import re
import sys

SOURCE_TOPS = ("common", "coordinator", "worker", "client", "bench", "tests")
SOURCE_SUFFIXES = (".h", ".cpp")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
CODE = re.compile(r"`([^`]+)`")
ANY = "any folder"


def read_table(root):
    """{folder: set of folders it may include, or None for any}, from docs/ARCHITECTURE.md."""
    with open(os.path.join(root, "docs", "ARCHITECTURE.md"), encoding="utf-8") as f:
        text = f.read()
    section = text.split("\n## Layers\n", 1)
    if len(section) < 2:
        sys.exit("docs/ARCHITECTURE.md has no '## Layers' section")
    table = {}
    for line in section[1].split("\n## ", 1)[0].splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not line.startswith("| `") or len(cells) < 2:
            continue
        folder = CODE.findall(cells[0])[0]
        table[folder] = None if cells[1] == ANY else set(CODE.findall(cells[1]))
    if not table:
        sys.exit("docs/ARCHITECTURE.md's '## Layers' section has no table of folders")
    return table


def folder_of(path, table):
    """The table's most specific folder holding `path`, or None."""
    best = None
    for folder in table:
        if path.startswith(folder + "/") and (best is None or len(folder) > len(best)):
            best = folder
    return best


def source_files(root):
    for top in SOURCE_TOPS:
        for directory, _, names in os.walk(os.path.join(root, top)):
            for name in sorted(names):
                if name.endswith(SOURCE_SUFFIXES):
                    yield os.path.relpath(os.path.join(directory, name), root)


def includes(root, path):
    """The repository files that `path` includes (generated and system files left out)."""
    with open(os.path.join(root, path), encoding="utf-8") as f:
        text = f.read()
    for number, line in enumerate(text.splitlines(), 1):
        for target in INCLUDE.findall(line):
            if os.path.isfile(os.path.join(root, target)):
                yield number, target


def header_cycles(graph):
    """Each include cycle among headers once, as a list of headers ending where it began."""
    cycles, state = [], {}  # state: 1 on the current path, 2 done
    for start in sorted(graph):
        if state.get(start):
            continue
        path, stack = [start], [iter(sorted(graph[start]))]
        state[start] = 1
        while stack:
            target = next(stack[-1], None)
            if target is None:
                state[path.pop()] = 2
                stack.pop()
            elif state.get(target) == 1:
                cycles.append(path[path.index(target):] + [target])
            elif not state.get(target):
                state[target] = 1
                path.append(target)
                stack.append(iter(sorted(graph.get(target, ()))))
    return cycles


def main():
    root = sys.argv[1]
    table = read_table(root)
    problems = ["the table names %s, which is not a folder" % folder
                for folder in sorted(table) if not os.path.isdir(os.path.join(root, folder))]
    headers = {}
    files = list(source_files(root))
    for path in files:
        folder = folder_of(path, table)
        if folder is None:
            problems.append("%s: in no folder of the table in docs/ARCHITECTURE.md" % path)
            continue
        allowed = table[folder]
        found = list(includes(root, path))
        if path.endswith(".h"):
            headers[path] = {target for _, target in found if target.endswith(".h")}
        for number, target in found:
            other = folder_of(target, table)
            if other == folder or allowed is None or other in allowed:
                continue
            problems.append("%s:%d: %s may not include %s (%s)"
                            % (path, number, folder, other or "an unlisted folder", target))
    for cycle in header_cycles(headers):
        problems.append("include cycle: " + " -> ".join(cycle))
    for p in problems:
        print(p)
    print("%d files, %d folders checked, %d problems" % (len(files), len(table), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
