#!/usr/bin/env python3
"""Keeps the docs and comments pointing at real things.

  doc_lint.py ROOT          lints the tree at ROOT (its git-tracked files, or
                            every file when ROOT is not a git checkout)
  doc_lint.py --self-test   plants one violation of each rule in a copy of a
                            small tree and fails unless each is caught

Rules:
  paths     every repository path named in the docs, comments and scripts
            (core/..., docs/..., tests/..., with {a,b} and [ch] expanded)
            exists; ALL-CAPS segments (NAME, DIR) are placeholders
  include   no "issue N" and no "the brief" in include/ (public headers say
            the reason, not the ticket)
  design    no mention of a DESIGN.md the repository does not have
  pictures  every pelt command of scripts/docs-images.sh appears verbatim in
            some doc (continuation lines joined, runs of blanks as one), so
            the pictures' commands cannot drift from the ones users read
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

TOP = "core|gl|scene|apps|platform|include|tests|scripts|docs|examples|cmake|scenes|web|packaging"
PATH = re.compile(r"(?<![\w/.$~-])((?:%s)/[\w.{},\[\]/-]*[\w}\]])(?![\w.*-]*\*)" % TOP)
TEXT = (".md", ".c", ".h", ".glsl", ".sh", ".txt", ".cmake", ".json", ".py", ".in", ".html", ".js")


def tree_files(root):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "--cached", "--others", "--exclude-standard"], capture_output=True, text=True, check=True).stdout
        files = [f for f in out.split("\n") if f]
        if files:
            return files
    except (OSError, subprocess.CalledProcessError):
        pass
    found = []
    for d, _, names in os.walk(root):
        for n in names:
            found.append(os.path.relpath(os.path.join(d, n), root))
    return found


def expand(tok):
    m = re.search(r"\{([^{}]*)\}", tok)
    if m:
        return [p for alt in m.group(1).split(",") for p in expand(tok[:m.start()] + alt + tok[m.end():])]
    m = re.search(r"\[([a-z]+)\]", tok)
    if m:
        return [p for ch in m.group(1) for p in expand(tok[:m.start()] + ch + tok[m.end():])]
    return [tok]


def read(root, f):
    try:
        with open(os.path.join(root, f), encoding="utf-8") as h:
            return h.read()
    except (OSError, UnicodeDecodeError):
        return None


def lint(root):
    files = tree_files(root)
    known = set(files)
    for f in files:
        while "/" in f:
            f = f.rsplit("/", 1)[0]
            known.add(f)
    problems = []
    for f in files:
        if not (f.endswith(TEXT) or os.path.basename(f) == "CMakeLists.txt"):
            continue
        # The test data, and this file, whose self-test plants what it must catch.
        if f.startswith(("tests/data/", "tests/fuzz/corpus")) or f == "tests/docs/doc_lint.py":
            continue
        text = read(root, f)
        if text is None:
            continue
        for n, line in enumerate(text.split("\n"), 1):
            if "DESIGN.md" in line:
                problems.append("%s:%d: names DESIGN.md, which is not in the repository" % (f, n))
            if f.startswith("include/") and re.search(r"\bissue #?\d+|\bthe brief\b", line, re.I):
                problems.append("%s:%d: says \"issue N\" or \"the brief\" in a public header" % (f, n))
            for tok in PATH.findall(line):
                tok = tok.rstrip(".,")
                if tok.endswith("]") and "[" not in tok:
                    tok = tok[:-1]
                if re.search(r"(^|/)[A-Z]{3,}(_|\.|/|$)", tok) or tok.endswith("_"):
                    continue
                for p in expand(tok):
                    if p.rstrip("/") not in known:
                        problems.append("%s:%d: names %s, which does not exist" % (f, n, p))
    script = read(root, "scripts/docs-images.sh")
    if script is not None:
        docs = "\n".join(read(root, f) or "" for f in files if f.endswith(".md"))
        norm = lambda s: re.sub(r"[ \t]+", " ", re.sub(r"\\\n\s*", " ", s))
        docs = norm(docs)
        for n, line in enumerate(norm(script).split("\n"), 1):
            cmd = re.sub(r"\s+#.*$", "", line.strip())
            if cmd.startswith("pelt ") and cmd not in docs:
                problems.append("scripts/docs-images.sh: `%s` is in no doc" % cmd)
    return problems


def self_test():
    tmp = tempfile.mkdtemp()
    try:
        os.makedirs(os.path.join(tmp, "docs"))
        os.makedirs(os.path.join(tmp, "include", "pelt"))
        os.makedirs(os.path.join(tmp, "scripts"))
        os.makedirs(os.path.join(tmp, "core", "base"))

        def write(path, text):
            with open(os.path.join(tmp, path), "w", encoding="utf-8") as h:
                h.write(text)

        write("core/base/a.c", "/* see core/base/a.h and docs/x.md */\n")
        write("core/base/a.h", "\n")
        write("docs/x.md", "Run `pelt render -o x.png`; code in core/base/a.{c,h}.\n")
        write("include/pelt/a.h", "/* a public header */\n")
        write("scripts/docs-images.sh", "img() {\n  pelt render -o x.png\n}\n")
        clean = lint(tmp)
        if clean:
            print("self-test: the clean tree fails:", clean)
            return 1
        plants = [
            ("core/base/a.c", "/* see core/base/gone.c */\n", "gone.c"),
            ("include/pelt/a.h", "/* fixed in issue 12 */\n", "issue N"),
            ("docs/x.md", "As DESIGN.md says.\n", "DESIGN.md"),
            ("scripts/docs-images.sh", "img2() {\n  pelt render --layers 8 -o y.png\n}\n", "in no doc"),
        ]
        for path, extra, what in plants:
            full = os.path.join(tmp, path)
            with open(full, encoding="utf-8") as h:
                before = h.read()
            write(path, before + extra)
            found = lint(tmp)
            write(path, before)
            if not any(what in p for p in found):
                print("self-test: a planted %s in %s was not caught" % (what, path))
                return 1
            print("self-test: caught:", found[0])
        return 0
    finally:
        shutil.rmtree(tmp)


def main():
    if len(sys.argv) == 2 and sys.argv[1] == "--self-test":
        return self_test()
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    problems = lint(sys.argv[1])
    for p in problems:
        print(p)
    if problems:
        print("doc_lint: %d problem(s)" % len(problems))
        return 1
    print("doc_lint: every path named exists, no ticket talk in include/, every picture command is in the docs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
