#!/usr/bin/env python3
"""The repository stands alone: its docs and comments cite only files inside it.

Every relative Markdown link in README.md and docs/ names a file that exists, and no tracked
file points at the design notes or source documents kept outside the repository.

usage: docs_test.py SOURCE_DIR
"""
import os
import re
import subprocess
import sys

OUTSIDE = re.compile(r"\b(DESIGN|STYLE)\.md\b|\.\./shared/|seeds/0\d\d_")
LINK = re.compile(r"\]\(([^)#\s]+)(#[^)]*)?\)")


def main():
    root = sys.argv[1]
    files = subprocess.run(["git", "-C", root, "ls-files"], check=True, capture_output=True,
                           text=True).stdout.split()
    problems = []
    for name in files:
        if name == "tests/docs/docs_test.py":
            continue
        path = os.path.join(root, name)
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except (UnicodeDecodeError, IsADirectoryError, FileNotFoundError):
            continue
        for number, line in enumerate(text.splitlines(), 1):
            if OUTSIDE.search(line):
                problems.append("%s:%d: cites a file outside the repository: %s"
                                % (name, number, line.strip()))
            if name.endswith(".md"):
                for target, _ in LINK.findall(line):
                    if re.match(r"[a-z]+:", target):
                        continue  # http:, https:, mailto:
                    linked = os.path.normpath(os.path.join(os.path.dirname(path), target))
                    if not os.path.exists(linked):
                        problems.append("%s:%d: links to %s, which does not exist"
                                        % (name, number, target))
    for p in problems:
        print(p)
    print("%d files checked, %d problems" % (len(files), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
