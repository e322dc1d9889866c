"""scripts/lint_cache.py: a key changes with everything clang-tidy reads, and only with that."""
import json
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

SCRIPT = pathlib.Path(__file__).resolve().parents[1] / "lint_cache.py"
TIDY_ARGS = "-quiet -checks=-*,clang-analyzer-*"


def make_project(root):
    """A checkout of one file including one header, and its compile database."""
    (root / "lib").mkdir(parents=True)
    (root / "build").mkdir()
    (root / ".clang-tidy").write_text("Checks: '-*,clang-analyzer-*'\n")
    (root / "lib" / "h.hpp").write_text("inline int twice(int x) { return 2 * x; }\n")
    (root / "lib" / "a.cpp").write_text('#include "h.hpp"\nint f() { return twice(3); }\n')
    write_database(root, ["-I", str(root / "lib")])


def write_database(root, flags):
    source = str(root / "lib" / "a.cpp")
    entry = {"directory": str(root / "build"), "file": source,
             "command": " ".join(["/usr/bin/c++", *flags, "-O2", "-std=c++20", "-o", "a.o", "-MD",
                                  "-MT", "a.o", "-MF", "a.o.d", "-c", source])}
    (root / "build" / "compile_commands.json").write_text(json.dumps([entry]))


def pending(root, *extra, tidy_args=TIDY_ARGS, files=("lib/a.cpp",)):
    done = subprocess.run([sys.executable, str(SCRIPT), "pending", "--db", "build", "--tidy-args",
                           tidy_args, "--record", "record.txt", "--keys", "keys.txt", *extra,
                           *files], cwd=root, capture_output=True, text=True, check=False)
    return done


def key(root, **kwargs):
    done = pending(root, **kwargs)
    assert done.returncode == 0, done.stderr
    return (root / "keys.txt").read_text().split()[0]


def record(root):
    subprocess.run([sys.executable, str(SCRIPT), "record", "--record", "record.txt", "keys.txt"],
                   cwd=root, check=True)


pytestmark = pytest.mark.skipif(not (shutil.which("clang++") and shutil.which("clang-tidy")),
                                reason="clang++ and clang-tidy needed")


def test_a_recorded_file_is_not_linted_again_until_its_input_changes(tmp_path):
    make_project(tmp_path)
    first = pending(tmp_path)
    assert first.stdout.split() == ["lib/a.cpp"]
    record(tmp_path)
    assert "lib/a.cpp" in (tmp_path / "record.txt").read_text()
    assert pending(tmp_path).stdout.split() == []
    assert pending(tmp_path, "--all").stdout.split() == ["lib/a.cpp"]
    # A comment in a header: NOLINT is one, so comments are part of the input.
    (tmp_path / "lib" / "h.hpp").write_text(
        "inline int twice(int x) { return 2 * x; }  // NOLINT\n")
    assert pending(tmp_path).stdout.split() == ["lib/a.cpp"]


def test_the_key_follows_what_clang_tidy_reads(tmp_path):
    make_project(tmp_path)
    base = key(tmp_path)
    assert key(tmp_path) == base  # deterministic
    assert key(tmp_path, tidy_args=TIDY_ARGS + ",misc-unused-using-decls") != base
    (tmp_path / ".clang-tidy").write_text("Checks: '-*,bugprone-*'\n")
    assert key(tmp_path) != base
    (tmp_path / ".clang-tidy").write_text("Checks: '-*,clang-analyzer-*'\n")
    assert key(tmp_path) == base
    write_database(tmp_path, ["-I", str(tmp_path / "lib"), "-DEXTRA=1"])
    assert key(tmp_path) != base


def test_a_header_moved_unchanged_changes_the_key(tmp_path):
    # The header filter reads the header's path: the same text found elsewhere, by the same
    # flags, is another input.
    make_project(tmp_path)
    (tmp_path / "lib" / "sub").mkdir()
    write_database(tmp_path, ["-I", str(tmp_path / "lib" / "sub"), "-I", str(tmp_path / "lib")])
    base = key(tmp_path)
    (tmp_path / "lib" / "h.hpp").rename(tmp_path / "lib" / "sub" / "h.hpp")
    assert key(tmp_path) != base


def test_clones_at_other_paths_share_keys(tmp_path):
    make_project(tmp_path / "one")
    make_project(tmp_path / "two" / "deeper")
    assert key(tmp_path / "one") == key(tmp_path / "two" / "deeper")


def test_a_file_that_does_not_preprocess_is_linted(tmp_path):
    make_project(tmp_path)
    (tmp_path / "lib" / "a.cpp").write_text('#include "missing.hpp"\n')
    done = pending(tmp_path)
    assert done.returncode == 0
    assert done.stdout.split() == ["lib/a.cpp"]
    assert (tmp_path / "keys.txt").read_text() == ""


def test_a_file_outside_the_database_is_refused_by_name(tmp_path):
    make_project(tmp_path)
    done = pending(tmp_path, files=("lib/a.cpp", "lib/b.cpp"))
    assert done.returncode != 0
    assert "lib/b.cpp" in done.stderr and "compile_commands.json" in done.stderr
    assert not os.path.exists(tmp_path / "record.txt")
