#!/usr/bin/env python3
"""Write src/code_order.txt: the functions a typical `condyn run` executes, for the linker to place
together (CMake option CONDYN_CODE_ORDER, issue 12).

Why: a run executes about 0.8 MB of condyn's 5.8 MB of code, spread over the whole binary; the
kernel maps code in 64 KB blocks around each page it faults in, so a 1,000-DOF run held 2.8 MB of
condyn's code resident (docs/benchmarks.md). Placed together, the same functions take 1.2 MB.

How: runs `condyn run` under valgrind's callgrind on the benchmark lattice of 1,000 DOFs
(bench/lattice.py; index1, GGL and elimination, from Matrix Market files with the full and the
condensed Newton solve, and as a truss2d scene) and on the README's first example
(models/scenes/quickstart.toml), and lists the mangled names of the functions
executed in the condyn binary as the input sections gold orders (`.text.NAME`, `.text.startup.NAME`
for main and static initializers, `.text.unlikely.NAME` for a cold part that ran). A
constructor or destructor is listed under its base-object name too (C2/D2), of which the
complete-object symbol callgrind sees is an alias.

Run it after changes that rename or add functions on the run path (a stale list only packs less:
functions it no longer names are placed as before):

    cmake --build build --target condyn
    /usr/bin/python3 bench/code_order.py            # needs valgrind (apt-get install valgrind)
    cmake --build build --target condyn             # relinks with the new list
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFINITION = re.compile(r"^(c?)(ob|fn)=\((\d+)\)(?: (.*))?$")
ALIASES = (("C1E", "C2E"), ("C1I", "C2I"), ("D1E", "D2E"))


def executed(profile, binary):
    """Mangled names of the functions callgrind saw executed in `binary`, in file order."""
    names, objects, functions, current = [], {}, {}, None
    with open(profile) as f:
        for line in f:
            m = DEFINITION.match(line.rstrip("\n"))
            if not m:
                continue
            called, kind, key, name = m.groups()
            table = objects if kind == "ob" else functions
            if name:
                table[key] = name
            if called:
                continue
            if kind == "ob":
                current = objects[key]
            elif current and os.path.realpath(current) == binary:
                name = functions[key].split("'")[0]  # callgrind's 'N recursion suffix
                if not name.startswith("0x"):  # code without a symbol (PLT stubs): no section
                    names.append(name)
    return names


def check(order_file, binary, least):
    """Exit status 0 when at least the fraction `least` of the functions the list names are
    functions of `binary` (nm): the list still describes this program."""
    names = set()
    with open(order_file) as f:
        for line in f:
            section = line.strip()
            for prefix in (".text.unlikely.", ".text.startup.", ".text."):
                if section.startswith(prefix):
                    names.add(section[len(prefix):])
                    break
    nm = subprocess.run(["nm", "--defined-only", binary], check=True, capture_output=True, text=True)
    defined = {line.split()[-1] for line in nm.stdout.splitlines() if line.strip()}
    found = len(names & defined) / max(1, len(names))
    verdict = "current" if found >= least else "stale: run bench/code_order.py"
    print(f"{order_file}: {found:.1%} of its {len(names)} names are functions of {binary} "
          f"(at least {least:.0%} wanted): {verdict}")
    return 0 if found >= least else 1


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--condyn", default=os.path.join(ROOT, "build", "condyn"))
    p.add_argument("--out", default=os.path.join(ROOT, "src", "code_order.txt"))
    p.add_argument("--check", type=float, metavar="FRACTION",
                   help="write nothing; fail unless this fraction of the listed functions exist")
    args = p.parse_args()
    binary = os.path.realpath(args.condyn)
    if not os.path.exists(binary):
        p.error(f"{binary} not found: build it first (cmake --build build --target condyn)")
    if args.check is not None:
        sys.exit(check(args.out, binary, args.check))
    with tempfile.TemporaryDirectory() as tmp:
        lattice = os.path.join(tmp, "lattice")
        subprocess.run([sys.executable, os.path.join(ROOT, "bench", "lattice.py"), "--dofs", "1e3",
                        "--out", lattice], check=True, stdout=subprocess.DEVNULL)
        runs = [(os.path.join(lattice, scene), scheme)
                for scene in ("lattice.toml", "condensed.toml", "inline.toml")
                for scheme in ("index1", "ggl", "elimination")]
        runs.append((os.path.join(ROOT, "models", "scenes", "quickstart.toml"), None))
        order = []
        for k, (scene, scheme) in enumerate(runs):
            profile = os.path.join(tmp, f"callgrind.{k}")
            cmd = ["valgrind", "--tool=callgrind", "--demangle=no", f"--callgrind-out-file={profile}",
                   binary, "run", scene, "--out", os.path.join(tmp, "out.csv")]
            if scheme:
                cmd[-2:-2] = ["--scheme", scheme]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            order += executed(profile, binary)
    sections = []
    for name in dict.fromkeys(order):
        if name.endswith(".cold"):  # the cold part GCC splits off: in .text.unlikely.NAME
            sections.append(".text.unlikely." + name[: -len(".cold")])
            continue
        for symbol in [name] + [name.replace(a, b) for a, b in ALIASES if a in name]:
            # GCC puts main and static initializers in .text.startup.NAME, the rest in .text.NAME
            sections += [".text." + symbol, ".text.startup." + symbol]
    # In the order the profiles first name them, which callgrind does not keep stable: lists
    # written twice differ in order, and so do their resident peaks (docs/benchmarks.md).
    sections = list(dict.fromkeys(sections))
    with open(args.out, "w") as f:
        f.write("\n".join(sections) + "\n")
    print(f"wrote {args.out}: {len(dict.fromkeys(order))} functions from {len(runs)} runs")


if __name__ == "__main__":
    main()
