"""IFToMM A03 written as rigid bodies (models/scenes/iftomm/A03_andrews.toml) against condyn's
built-in Andrews model (models/scenes/andrews.toml): the same mechanism in two formulations, seven
absolute angles with six loop closures against natural coordinates with ten revolute joints.
Each body's angle of the scene is a sum of the built-in model's angles (the scene's header):
body1 beta, body2 beta + Theta, body3 gamma, body4 Phi + delta, body5 delta, body6 Omega +
epsilon, body7 epsilon. Both are run by the condyn command over the whole 0.03 s under one
scheme and tolerances, and compared at every output time.

    /usr/bin/python3 validation/iftomm/andrews_agreement.py --condyn build/condyn \\
        --figure docs/figures/A03_andrews_agreement.png

prints the largest difference per body with its bound (agreement_bound) and draws beta(t) from
both runs and each body's difference against t. Exit 1 when a difference exceeds its bound.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import runs as ir  # noqa: E402

BUILT_IN = os.path.join(ir.ROOT, "models", "scenes", "andrews.toml")
MULTIBODY = os.path.join(ir.ROOT, "models", "scenes", "iftomm", "A03_andrews.toml")
# Each body's angle as the built-in model's angles it adds up.
ANGLES = {"body1": ("beta",), "body2": ("beta", "Theta"), "body3": ("gamma",),
          "body4": ("Phi", "delta"), "body5": ("delta",), "body6": ("Omega", "epsilon"),
          "body7": ("epsilon",)}
# The validation suite's factor on rtol (docs/validation.md): global error builds up over about
# 10^3 steps; two runs, each within it of the exact motion.
RTOL_FACTOR = 1000.0


def run_both(condyn, work_dir, scheme="ggl", rtol=1e-10, atol=1e-12):
    """Runs both models under `scheme` at rtol and atol; returns (t, built-in columns, the
    scene's columns)."""
    columns = []
    for scene, stem in ((BUILT_IN, "builtin"), (MULTIBODY, "multibody")):
        out = os.path.join(work_dir, f"andrews_{stem}.csv")
        subprocess.run([str(condyn), "run", scene, "--scheme", scheme, "--rtol", str(rtol),
                        "--atol", str(atol), "--out", out], check=True, capture_output=True)
        columns.append(ir.read_csv(out))
    builtin, multibody = columns
    if not np.array_equal(builtin["t"], multibody["t"]):
        raise ValueError("the two runs' output times differ")
    return builtin["t"], builtin, multibody


def built_in_angle(builtin, body):
    return sum(builtin[name] for name in ANGLES[body])


def agreement_bound(builtin, body, rtol):
    """RTOL_FACTOR x rtol x the angle's scale: its largest magnitude over the run, at least
    1 rad (the angles are O(1); beta turns 2.5 times)."""
    return RTOL_FACTOR * rtol * max(1.0, float(np.max(np.abs(built_in_angle(builtin, body)))))


def differences(builtin, multibody):
    """Each body's angle from the scene minus the built-in model's, at every output time."""
    return {body: multibody[f"{body}.angle"] - built_in_angle(builtin, body) for body in ANGLES}


def draw(path, t, builtin, multibody, run_label):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    import figure_style as style
    style.paper_style(plt)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(style.PAGE_WIDTH, 4.6), sharex=True)
    top.plot(t * 1e3, builtin["beta"], "k-", label="built-in model (7 angles)")
    top.plot(t * 1e3, multibody["body1.angle"], "C1--", label="rigid-body scene (body1.angle)")
    top.set_ylabel(r"$\beta$ [rad]")
    top.legend(loc="upper left", frameon=False)
    for k, (body, diff) in enumerate(differences(builtin, multibody).items()):
        bottom.plot(t[1:] * 1e3, np.maximum(np.abs(diff[1:]), 1e-18), f"C{k}-", label=body)
    style.log_axis(bottom)
    bottom.set_xlabel("t [ms]")
    bottom.set_ylabel("|scene - built-in| [rad]")
    style.title(fig, "IFToMM A03 (Andrews' mechanism): the rigid-body scene against the "
                     f"built-in model, {run_label}")
    legend = style.legend_below(fig, bottom.get_lines(), ncol=7)
    style.fit(fig, legend)
    fig.savefig(path, dpi=150)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--condyn", default=os.path.join(ir.ROOT, "build", "condyn"))
    p.add_argument("--scheme", default="ggl")
    p.add_argument("--rtol", type=float, default=1e-10)
    p.add_argument("--figure", help="write the figure here (PNG, PDF or SVG)")
    args = p.parse_args(argv)
    with tempfile.TemporaryDirectory() as work:
        t, builtin, multibody = run_both(args.condyn, work, args.scheme, args.rtol)
    ok = True
    for body, diff in differences(builtin, multibody).items():
        worst, bound = float(np.max(np.abs(diff))), agreement_bound(builtin, body, args.rtol)
        ok &= worst <= bound
        print(f"{body}: max |scene - built-in| = {worst:.3e} rad (bound {bound:.1e})")
    if args.figure:
        draw(args.figure, t, builtin, multibody, f"{args.scheme} at rtol {args.rtol:g}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
