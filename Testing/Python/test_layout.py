#!/usr/bin/env python3
"""The house rules of Documentation/architecture.md, checked on the sources.

    python3 test_layout.py [SOURCE_DIR]

- No product file (the sources under Core/, Filters/, IO/, Rendering/,
  Module/, Applications/ and Examples/) is over 700 lines.
- A header named *Private.h is included only by files in its own folder:
  what modules share is a header without that suffix.

Prints one line per breach and exits 1 if there is any.
"""
import os
import re
import sys

SOURCE_DIR = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                             os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
PRODUCT = ("Core", "Filters", "IO", "Rendering", "Module", "Applications", "Examples")
SOURCE_SUFFIXES = (".h", ".cxx", ".py", ".xml")
LONGEST = 700
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+Private\.h)"', re.MULTILINE)


def files(top, suffixes):
    for folder, names, found in os.walk(os.path.join(SOURCE_DIR, top)):
        names[:] = [n for n in names if not n.startswith(".")]
        for name in found:
            if name.endswith(suffixes):
                yield os.path.join(folder, name)


def main():
    breaches = []
    private_homes = {}
    for top in PRODUCT:
        for path in files(top, SOURCE_SUFFIXES):
            with open(path, encoding="utf-8", errors="replace") as f:
                lines = f.read().count("\n")
            if lines > LONGEST:
                breaches.append("%s has %d lines (at most %d)" % (os.path.relpath(path, SOURCE_DIR), lines, LONGEST))
            if path.endswith("Private.h"):
                private_homes.setdefault(os.path.basename(path), []).append(os.path.dirname(path))
    checked = 0
    for top in PRODUCT + ("Testing",):
        for path in files(top, (".h", ".cxx")):
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
            for header in INCLUDE.findall(text):
                homes = private_homes.get(os.path.basename(header), [])
                checked += 1
                if homes and os.path.dirname(path) not in homes:
                    breaches.append("%s includes %s, private to %s" % (
                        os.path.relpath(path, SOURCE_DIR), header,
                        " and ".join(os.path.relpath(h, SOURCE_DIR) for h in homes)))
    for breach in breaches:
        print("FAIL: " + breach)
    print("%d private includes checked, %d breaches" % (checked, len(breaches)))
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
