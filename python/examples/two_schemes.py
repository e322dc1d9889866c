"""A spring-mass chain built from numpy and scipy.sparse arrays, with two multi-freedom
constraints, run under two schemes (GGL and Baumgarte) at rtol 1e-6; their constraint drift and
their error against a tight reference (elimination, rtol 1e-12) plotted side by side.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/two_schemes.py [OUT.png]
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import scipy.sparse as sp  # noqa: E402

import condyn  # noqa: E402

# The model: n unit masses (kg) in a line, springs of 1000 N/m between them and to a wall on the
# left; mass 5 and mass 15 move together (u5 = u15), mass 10 stays midway between 9 and 11
# (u9 + u11 = 2 u10); a harmonic force of 10 N at 5 rad/s on the last mass.
n = 20
k = 1000.0
K = sp.diags([np.full(n - 1, -k), np.full(n, 2 * k), np.full(n - 1, -k)], [-1, 0, 1], format="lil")
K[n - 1, n - 1] = k  # the last mass has one spring
A = sp.csr_matrix(([1.0, -1.0, 1.0, -2.0, 1.0], ([0, 0, 1, 1, 1], [4, 14, 8, 9, 10])),
                  shape=(2, n))
f = np.zeros(n)
f[-1] = 1.0
scene = {
    "model": {"type": "matrix", "mass": sp.identity(n, format="csr"), "stiffness": K.tocsr()},
    "constraint_block": [{"file": A, "name": "mfc"}],
    "load": [{"pattern": f, "value": {"type": "harmonic", "amplitude": 10.0, "omega": 5.0}}],
    "solve": {"t_end": 10.0, "output_step": 0.02},
}

reference = condyn.run(scene, scheme="elimination", rtol=1e-12, atol=1e-14)
runs = {s: condyn.run(scene, scheme=s, rtol=1e-6, atol=1e-8) for s in ("ggl", "baumgarte")}

fig, (ax_drift, ax_error) = plt.subplots(1, 2, figsize=(8, 3.2), constrained_layout=True)
for scheme, r in runs.items():
    error = np.max(np.abs(r.u - reference.u), axis=1)  # max over the DOFs, metres
    ax_drift.semilogy(r.t[1:], r.drift[1:, 0], label=scheme)
    ax_error.semilogy(r.t[1:], error[1:], label=scheme)
    print(f"{scheme:9s} {r.summary['steps']:5d} steps  max drift {r.drift[:, 0].max():.2e} m  "
          f"max error {error.max():.2e} m  (amplitude {np.abs(reference.u).max():.3f} m)")
ax_drift.set(title="constraint drift |A u|", xlabel="t (s)", ylabel="max over rows (m)")
ax_error.set(title="error against elimination, rtol 1e-12", xlabel="t (s)",
             ylabel="max over DOFs |u - u_ref| (m)")
for ax in (ax_drift, ax_error):
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(title="rtol 1e-6")
out = sys.argv[1] if len(sys.argv) > 1 else "two_schemes.png"
fig.savefig(out, dpi=150)
print(f"wrote {out}")
