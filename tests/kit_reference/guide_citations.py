#!/usr/bin/env python3
"""docs/writing_a_technique.md is read from the package (share/doc/shadowbench/):
what it cites must be there too. It may name no file of the source tree that is not installed (tests/, harness/, scripts/,
techniques/, bench/, tools/) nor an issue by number; every header it names
as "core/x.h", "gl/x.h", "plugin/x.h" or "common/x.h" is an installed header
(harness/core/, harness/gl/, harness/plugin/, techniques/common/); every
Markdown link to a page is a page of docs/.

  guide_citations.py SOURCE_DIR   exit 1 naming the first bad citation
"""
import os
import re
import sys

NOT_INSTALLED = re.compile(r"(?<![\w/<>.-])(tests|harness|scripts|techniques|bench|tools)/[\w./-]*")
ISSUE = re.compile(r"\bissues? \d+")
HEADER = re.compile(r"`((core|gl|plugin|common)/\w+\.h)`")
LINK = re.compile(r"\]\(([\w./-]+\.md)(#[\w-]*)?\)")
INSTALLED_HEADER_DIRS = {"core": "harness/core", "gl": "harness/gl", "plugin": "harness/plugin",
                         "common": "techniques/common"}


def main():
    source = sys.argv[1]
    path = os.path.join(source, "docs", "writing_a_technique.md")
    with open(path) as f:
        lines = f.read().split("\n")
    problems = []
    for n, line in enumerate(lines, 1):
        for m in NOT_INSTALLED.finditer(line):
            problems.append(f"{n}: cites {m.group(0)}, which the package does not install")
        for m in ISSUE.finditer(line):
            problems.append(f"{n}: cites '{m.group(0)}', which a reader of the package cannot see")
        for m in HEADER.finditer(line):
            folder, name = m.group(2), os.path.basename(m.group(1))
            if not os.path.isfile(os.path.join(source, INSTALLED_HEADER_DIRS[folder], name)):
                problems.append(f"{n}: names {m.group(1)}, which is no installed header")
        for m in LINK.finditer(line):
            if not os.path.isfile(os.path.join(source, "docs", m.group(1))):
                problems.append(f"{n}: links {m.group(1)}, which is no page of docs/")
    if problems:
        print(f"{path}:{problems[0]}" + (f" (and {len(problems) - 1} more)" if problems[1:] else ""))
        return 1
    print("writing_a_technique.md cites installed files only")
    return 0


if __name__ == "__main__":
    sys.exit(main())
