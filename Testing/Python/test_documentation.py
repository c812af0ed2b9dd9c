#!/usr/bin/env python3
"""The README and Documentation/*.md say what works; this test holds them to it.

    python3 test_documentation.py [SOURCE_DIR]

- Every ```python block of README.md, and every block of Documentation/*.md
  whose fence follows the line <!-- test: run -->, runs in a fresh process of
  this Python with the repository root as working directory (so paths like
  Testing/Data/... and ../shared/data/... resolve as written). A block that
  names a ../shared/data file that is missing is skipped, and fails where
  CI=true. A block fails on a non-zero exit status or a VTK error report.
- Every ```cpp block of README.md follows a line <!-- source: PATH -->, and
  each of its lines appears, in order, in that file (a program a test builds
  and runs), so the snippet compiles as the file does.
- Every relative link and image of README.md and Documentation/*.md reaches a
  file, an anchor reaches a heading of its page, and README.md links every
  page of Documentation/.

Prints one line per check and exits 1 if any failed.
"""
import os
import re
import subprocess
import sys

SOURCE_DIR = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                             os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
RUN_MARK = "<!-- test: run -->"
SOURCE_MARK = re.compile(r"^<!--\s*source:\s*(\S+)\s*-->$")
FENCE = re.compile(r"^(\s*)(```+|~~~+)\s*([\w+-]*)")
SHARED = re.compile(r"\.\./shared/data/[^\s\"')]+")
REQUIRED = os.environ.get("CI", "").lower() == "true"
VTK_ERROR = re.compile(r"ERROR: In |\sERR\| ")  # vtkErrorMacro, as printed and as vtkLogger writes it

failures = []


def fail(message):
    failures.append(message)
    print("FAIL: " + message)


def relative(path):
    return os.path.relpath(path, SOURCE_DIR)


def pages():
    """README.md and the Markdown pages directly under Documentation/."""
    documentation = os.path.join(SOURCE_DIR, "Documentation")
    names = sorted(name for name in os.listdir(documentation) if name.endswith(".md"))
    return [os.path.join(SOURCE_DIR, "README.md")] + [os.path.join(documentation, name) for name in names]


def blocks(path):
    """(language, first line number, code, the last non-blank line before the fence)."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    found = []
    i = 0
    while i < len(lines):
        match = FENCE.match(lines[i])
        if not match:
            i += 1
            continue
        indent, fence, language = match.groups()
        previous = next((lines[k].strip() for k in range(i - 1, -1, -1) if lines[k].strip()), "")
        body = []
        i += 1
        while i < len(lines) and not lines[i].strip().startswith(fence):
            line = lines[i]
            body.append(line[len(indent):] if line.startswith(indent) else line.lstrip())
            i += 1
        found.append((language.lower(), i - len(body), "\n".join(body) + "\n", previous))
        i += 1
    return found


def run_python_blocks():
    readme = os.path.join(SOURCE_DIR, "README.md")
    count = 0
    for path in pages():
        for language, line, code, previous in blocks(path):
            if language != "python" or (path != readme and previous != RUN_MARK):
                continue
            count += 1
            where = "%s:%d" % (relative(path), line)
            missing = [name for name in SHARED.findall(code)
                       if not os.path.exists(os.path.normpath(os.path.join(SOURCE_DIR, name)))]
            if missing:
                if REQUIRED:
                    fail("%s: %s is missing, and CI=true requires the shared data" % (where, missing[0]))
                else:
                    print("skipped %s: %s is missing (required where CI=true)" % (where, missing[0]))
                continue
            try:
                result = subprocess.run([sys.executable, "-c", code], cwd=SOURCE_DIR,
                                        stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                        universal_newlines=True, timeout=600)
            except subprocess.TimeoutExpired:
                fail("%s: the block did not finish within 600 s" % where)
                continue
            if result.returncode != 0:
                fail("%s: the block exited with %d:\n%s" % (where, result.returncode, result.stdout))
            elif VTK_ERROR.search(result.stdout):
                fail("%s: the block reported a VTK error:\n%s" % (where, result.stdout))
            else:
                print("ran %s: %s" % (where, result.stdout.strip().replace("\n", " | ")[:200]))
    if count == 0:
        fail("README.md holds no ```python block")


def check_cpp_blocks():
    readme = os.path.join(SOURCE_DIR, "README.md")
    count = 0
    for language, line, code, previous in blocks(readme):
        if language not in ("cpp", "c++", "cxx"):
            continue
        count += 1
        where = "README.md:%d" % line
        match = SOURCE_MARK.match(previous)
        if not match:
            fail("%s: a C++ block must follow <!-- source: PATH --> naming the file it is taken from" % where)
            continue
        source = os.path.join(SOURCE_DIR, match.group(1))
        if not os.path.isfile(source):
            fail("%s: %s does not exist" % (where, match.group(1)))
            continue
        with open(source, encoding="utf-8") as f:
            file_lines = [l.strip() for l in f.read().split("\n")]
        position = 0
        for snippet_line in (l.strip() for l in code.split("\n")):
            if not snippet_line:
                continue
            try:
                position = file_lines.index(snippet_line, position) + 1
            except ValueError:
                fail("%s: %r is not in %s (in this order)" % (where, snippet_line, match.group(1)))
                break
        else:
            print("C++ block %s: every line is in %s, in order" % (where, match.group(1)))
    if count == 0:
        fail("README.md holds no ```cpp block")


def slug(heading):
    """GitHub's anchor of a heading."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # links: their text
    text = re.sub(r"<[^>]+>", "", text).strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def anchors(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    seen = {}
    result = set()
    in_fence = False
    for line in text.split("\n"):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        match = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if match and not in_fence:
            base = slug(match.group(1))
            n = seen.get(base, 0)
            seen[base] = n + 1
            result.add(base if n == 0 else "%s-%d" % (base, n))
    return result


def links(path):
    """(line number, target) of the Markdown links and images outside code."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    found = []
    in_fence = False
    for number, line in enumerate(lines, 1):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        line = re.sub(r"`[^`]*`", "", line)
        for target in re.findall(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", line):
            found.append((number, target))
    return found


def check_links():
    readme = os.path.join(SOURCE_DIR, "README.md")
    linked = set()
    for path in pages():
        checked = 0
        for number, target in links(path):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):
                continue  # http:, https:, mailto:
            where = "%s:%d" % (relative(path), number)
            file_part, _, anchor = target.partition("#")
            resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            checked += 1
            if not os.path.exists(resolved):
                fail("%s: the link %s reaches no file" % (where, target))
                continue
            if path == readme:
                linked.add(resolved)
            if anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
                fail("%s: the link %s names no heading of %s" % (where, target, relative(resolved)))
        print("links of %s: %d checked" % (relative(path), checked))
    for path in pages()[1:]:
        if path not in linked:
            fail("README.md does not link %s" % relative(path))


run_python_blocks()
check_cpp_blocks()
check_links()
if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("the documentation holds")
