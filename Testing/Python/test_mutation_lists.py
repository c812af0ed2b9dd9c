#!/usr/bin/env python3
"""The mutation audit's lists still apply to the sources.

    python3 test_mutation_lists.py [SOURCE_DIR]

Testing/Mutations/run-mutations refuses a mutation whose `old` text does not
occur exactly once in its file; a change to the sources can leave an entry
behind, and the fault it plants then goes unchecked until someone runs the
audit. This checks every entry of every list, without building anything.

Prints one line per stale entry and exits 1 if there is any.
"""
import glob
import json
import os
import sys

SOURCE_DIR = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                             os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def stale_entries(path):
    """(list, name, occurrences) of each entry of one list that does not apply."""
    with open(path, encoding="utf-8") as f:
        entries = json.load(f)
    for entry in entries:
        with open(os.path.join(SOURCE_DIR, entry["file"]), encoding="utf-8") as f:
            count = f.read().count(entry["old"])
        if count != 1:
            yield os.path.relpath(path, SOURCE_DIR), entry["name"], count


def main():
    lists = sorted(glob.glob(os.path.join(SOURCE_DIR, "Testing", "Mutations", "*.json")))
    stale = [s for path in lists for s in stale_entries(path)]
    for path, name, count in stale:
        print("FAIL: %s: %r: its old text occurs %d times in its file, not once" % (path, name, count))
    print("%d lists checked, %d stale entries" % (len(lists), len(stale)))
    return 1 if stale or not lists else 0


if __name__ == "__main__":
    sys.exit(main())
