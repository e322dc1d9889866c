#!/usr/bin/env python3
"""Plot for the output folder of `condyn stress`.

Draws stress_map (PNG and SVG) into DIR: one row per generated case (family and parameter), one
column per scheme, each cell coloured by the run's verdict (holds, inaccurate, failed, refused;
blank where the scheme is not part of the family) and labelled with the error against the
reference (holds, inaccurate) or the verdict.

Run:   /usr/bin/python3 validation/plot_stress.py DIR
Needs: matplotlib and numpy (Debian: apt-get install python3-matplotlib python3-numpy).
Input: DIR/stress.csv as defined in validation/stress-output.md.

Exit status: 0 done, 1 the plot raised an error, 2 bad usage, no stress.csv, or one that condyn
stress would not have written (named with the problem), 3 matplotlib not importable.
"""
import csv
import os
import sys

from compare_files import SCHEME_ORDER as SCHEMES, num
VERDICTS = {  # colour, legend text
    "holds": ("#4daf4a", "holds (error within the case's limit)"),
    "inaccurate": ("#ff9f1c", "inaccurate (finished, error beyond the limit)"),
    "failed": ("#e41a1c", "failed (the integrator gave up)"),
    "refused": ("#bdbdbd", "refused (scene or scheme said no)"),
}


class BadData(Exception):
    """stress.csv is not what condyn stress writes: named with the problem."""


def read_rows(path):
    """stress.csv's rows, each with the columns the map needs."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            rows = list(reader)
            header = reader.fieldnames or []
    except UnicodeDecodeError as e:
        raise BadData(f"{path}: not UTF-8 text (byte 0x{e.object[e.start]:02x})") from None
    except (csv.Error, OSError) as e:
        raise BadData(f"{path}: {e}") from None
    missing = [c for c in ("case", "family", "label", "scheme", "status") if c not in header]
    if missing:
        raise BadData(f"{path}: no column {', '.join(missing)} (not written by condyn stress)")
    if not rows:
        raise BadData(f"{path}: no rows")
    for line, r in enumerate(rows, start=2):
        if None in r or any(v is None for v in r.values()):
            raise BadData(f"{path}:{line}: the row's cells do not match the header's columns")
    return rows


def main(argv):
    if len(argv) != 2 or not os.path.isfile(os.path.join(argv[1], "stress.csv")):
        print("usage: plot_stress.py DIR   (DIR: output folder of `condyn stress`, with "
              "stress.csv)", file=sys.stderr)
        return 2
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.patches import Patch
    except ImportError:
        print("plot_stress: matplotlib not available, plot skipped")
        return 3
    d = argv[1]
    try:
        rows = read_rows(os.path.join(d, "stress.csv"))
    except BadData as e:
        print(f"plot_stress: {e}", file=sys.stderr)
        return 2
    cases = list(dict.fromkeys((r["case"], f'{r["family"]}: {r["label"]}') for r in rows))
    schemes = [s for s in SCHEMES if any(r["scheme"] == s for r in rows)]
    schemes += sorted({r["scheme"] for r in rows} - set(schemes))
    cell = {(r["case"], r["scheme"]): r for r in rows}
    try:
        # 1.1 in per scheme, beside the case labels and the legend (about 4 in together)
        fig, ax = plt.subplots(figsize=(4.0 + 1.1 * len(schemes), 1.6 + 0.32 * len(cases)))
        for i, (case, _) in enumerate(cases):
            for j, scheme in enumerate(schemes):
                r = cell.get((case, scheme))
                if r is None:
                    continue
                colour = VERDICTS.get(r["status"], ("#ffffff", ""))[0]
                ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, color=colour, ec="white"))
                err = num(r.get("error_u"))
                if r["status"] in ("holds", "inaccurate") and err is not None:
                    text = f"{err:.0e}" if err > 0 else "0"
                elif r["status"] == "holds":
                    text = "no ref"  # finished, but not even a tight run gives a reference
                else:
                    text = {"failed": "fail", "refused": "n/a"}.get(r["status"], "")
                ax.text(j, i, text, ha="center", va="center", fontsize=7)
        ax.set_xlim(-0.5, len(schemes) - 0.5)
        ax.set_ylim(len(cases) - 0.5, -0.5)
        ax.set_xticks(range(len(schemes)), schemes)  # 1.1 in per scheme: room without a slant
        ax.set_yticks(range(len(cases)), [label for _, label in cases], fontsize=8)
        ax.set_title("condyn stress: where each scheme holds and where it breaks\n"
                     "(cell text: relative error of u against the case's reference)",
                     fontsize=11)
        ax.legend(handles=[Patch(color=c, label=t) for c, t in VERDICTS.values()],
                  loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
        fig.tight_layout()
        for ext in ("png", "svg"):
            fig.savefig(os.path.join(d, f"stress_map.{ext}"), dpi=130)
        plt.close(fig)
        print("plot_stress: wrote stress_map.png, stress_map.svg")
    except Exception as e:  # report, do not crash the caller
        print(f"plot_stress: failed: {type(e).__name__}: {e}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
