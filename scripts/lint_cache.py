#!/usr/bin/env python3
"""clang-tidy's verdicts, kept by the exact input they were reached on.

The test command's lint runs clang-tidy over every library file: the analyzer file by file and
the other checks over the unity batches, half the command's CPU (docs/benchmarks.md).
A verdict depends only on clang-tidy, its checks and arguments, .clang-tidy, the file's compile
flags and the text the compiler sees, which the flags and the files the compiler reads determine.
So a file's key is the SHA-256 of all of them: the flags, and the path and contents of every file
its preprocessing reads (the file and every header it includes, system headers too: the list
clang-scan-deps gives, in a tenth of the time of preprocessing the file), with the checkout's
path replaced by a placeholder so that clones elsewhere share keys. The record
(scripts/lint-record.txt, committed) holds the keys of the last clean lint; the test command lints
the files whose key it does not hold and, when they are clean, writes the record anew. A change
to a header changes the key of every file that includes it; a new clang, Eigen or flag, every key.

  lint_cache.py pending --db DIR --tidy-args A --record R --keys OUT [--all] FILE...
      print the files to lint (those whose key R does not hold; every file with --all) and
      write each file's key and path to OUT
  lint_cache.py record --record R KEYS...
      write R from the keys files of passes that were clean
"""
import argparse
import hashlib
import json
import os
import shlex
import shutil
import subprocess
import sys
import tempfile

ROOT_PLACEHOLDER = "<checkout>"
# Flags that name outputs or dependency files, not what the compiler reads: (flag, takes a value).
OUTPUT_FLAGS = {"-o": True, "-MF": True, "-MT": True, "-MQ": True, "-c": False, "-MD": False,
                "-MMD": False}


def compile_entries(db_dir):
    """The compile database's entries by the absolute path of their file."""
    path = os.path.join(db_dir, "compile_commands.json")
    with open(path, encoding="utf-8") as f:
        entries = json.load(f)
    by_file = {}
    for e in entries:
        args = e.get("arguments") or shlex.split(e["command"])
        by_file[os.path.normpath(os.path.join(e["directory"], e["file"]))] = (e["directory"], args)
    return by_file


def input_flags(args):
    """The compile command's flags without the compiler, the source and the output flags."""
    kept, skip = [], False
    for a in args[1:]:
        if skip:
            skip = False
        elif a in OUTPUT_FLAGS:
            skip = OUTPUT_FLAGS[a]
        elif not a.startswith("-") and a.endswith((".cpp", ".cxx", ".cc")):
            continue  # the source file itself
        else:
            kept.append(a)
    return kept


def scan_deps_program():
    """clang-scan-deps, unversioned or as Debian names LLVM 14's (clang-tools-14, which
    clang-tidy-14 depends on)."""
    for name in ("clang-scan-deps", "clang-scan-deps-14"):
        if shutil.which(name):
            return shutil.which(name)
    sys.exit("lint_cache.py: clang-scan-deps not found (Debian: clang-tools-14)")


def dependencies(files, entries):
    """Each file's inputs, the file first and then every header its preprocessing reads, by
    clang-scan-deps over the files' own flags under clang++ (as clang-tidy reads them); a file
    that does not preprocess is absent."""
    compiler = shutil.which("clang++") or "clang++"
    database = [{"directory": entries[f][0], "file": f,
                 "arguments": [compiler, *input_flags(entries[f][1]),
                               "-Wno-unknown-warning-option", "-w", "-c", f]} for f in files]
    with tempfile.TemporaryDirectory() as scratch:
        path = os.path.join(scratch, "compile_commands.json")
        with open(path, "w", encoding="utf-8") as out:
            json.dump(database, out)
        done = subprocess.run([scan_deps_program(), f"-compilation-database={path}",
                               "-format=make", f"-j={os.cpu_count() or 2}"],
                              capture_output=True, text=True, check=False)
    found = {}
    # Make rules: "target: dep dep \" continued over lines; the first dependency is the file, as
    # the database names it (absolute); any other path relative to its entry's directory.
    for rule in done.stdout.replace("\\\n", " ").split("\n"):
        names = rule.split(":", 1)[1].split() if ":" in rule else []
        if not names or os.path.normpath(names[0]) not in entries:
            continue
        file = os.path.normpath(names[0])
        found[file] = [os.path.normpath(os.path.join(entries[file][0], d)) for d in names]
    return found


def file_key(inputs, entry, context, root, digest_of):
    """SHA-256 of the pass's context, the file's flags and the path and contents of every input,
    or None when an input cannot be read (the file is then linted)."""
    h = hashlib.sha256()
    h.update(context)
    h.update("\0".join(input_flags(entry[1])).replace(root, ROOT_PLACEHOLDER).encode())
    for path in inputs:
        h.update(b"\0")
        h.update(path.replace(root, ROOT_PLACEHOLDER).encode())
        h.update(b"\0")
        try:
            h.update(digest_of(path))
        except OSError:
            return None
    return h.hexdigest()


def content_digests():
    """A function giving a file's SHA-256, each file read once (the headers are shared)."""
    cache = {}

    def digest(path):
        if path not in cache:
            with open(path, "rb") as f:
                cache[path] = hashlib.sha256(f.read()).digest()
        return cache[path]
    return digest


def pass_context(tidy_args, root):
    """What every file of a pass shares: clang-tidy's version (without the host's CPU) and
    arguments, and every .clang-tidy of the checkout with its path."""
    version = subprocess.run(["clang-tidy", "--version"], capture_output=True, text=True,
                             check=True).stdout
    # Its "Host CPU:" line names the machine, not clang-tidy: CI hosts differ in it, and with it
    # every key (a fresh machine relinted all 209 files, some 1,500 s of CPU).
    version = "\n".join(line for line in version.splitlines()
                        if not line.strip().startswith("Host CPU:"))
    parts = [version, tidy_args]
    for folder, dirs, names in sorted(os.walk(root)):
        dirs[:] = sorted(d for d in dirs if not d.startswith((".git", "build")))
        if ".clang-tidy" in names:
            with open(os.path.join(folder, ".clang-tidy"), encoding="utf-8") as f:
                parts += [os.path.relpath(folder, root), f.read()]
    return "\0".join(parts + [""]).encode()


def read_record(path):
    if not os.path.exists(path):
        return set()
    with open(path, encoding="utf-8") as f:
        return {line.split()[0] for line in f if line.strip() and not line.startswith("#")}


def pending(opts):
    root = os.path.realpath(os.getcwd())
    entries = compile_entries(opts.db)
    context = pass_context(opts.tidy_args, root)
    files = [os.path.normpath(os.path.join(root, f)) for f in opts.files]
    missing = [f for f in files if f not in entries]
    if missing:
        sys.exit(f"lint_cache.py: not in {opts.db}/compile_commands.json: {' '.join(missing)}")
    found = dependencies(files, entries)
    digest_of = content_digests()
    keys = [file_key(found[f], entries[f], context, root, digest_of) if f in found else None
            for f in files]
    clean = set() if opts.all else read_record(opts.record)
    with open(opts.keys, "w", encoding="utf-8") as out:
        for f, key in zip(files, keys):
            shown = os.path.relpath(f, root)
            if key is not None:
                out.write(f"{key}  {shown}\n")
            if key is None or key not in clean:
                print(shown)


def record(opts):
    lines = set()
    for path in opts.keys:
        with open(path, encoding="utf-8") as f:
            lines.update(line.rstrip("\n") for line in f if line.strip())
    with open(opts.record, "w", encoding="utf-8") as out:
        out.write("# clang-tidy found nothing in these inputs (scripts/lint_cache.py: the key is\n"
                  "# the SHA-256 of the pass, the flags and every file the compiler reads).\n"
                  "# Written by the test command after a clean lint; commit it with the change\n"
                  "# it records.\n")
        for line in sorted(lines, key=lambda s: (s.split(None, 1)[1], s)):
            out.write(line + "\n")


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    q = sub.add_parser("pending", help="print the files to lint, write their keys")
    q.add_argument("--db", required=True, help="build folder holding compile_commands.json")
    q.add_argument("--tidy-args", required=True, help="the pass's arguments to clang-tidy")
    q.add_argument("--record", required=True)
    q.add_argument("--keys", required=True, help="where to write each file's key")
    q.add_argument("--all", action="store_true", help="lint every file, whatever the record")
    q.add_argument("files", nargs="+")
    r = sub.add_parser("record", help="write the record from clean passes' keys")
    r.add_argument("--record", required=True)
    r.add_argument("keys", nargs="+")
    opts = p.parse_args()
    pending(opts) if opts.command == "pending" else record(opts)


if __name__ == "__main__":
    main()
