#!/usr/bin/python3
"""IFToMM A05, the stiff flyball governor, in minimal coordinates (phi, s, theta1, theta2).

Data (http://lim.ii.udc.es/mbsbenchmark/dist/A05/A05_specification.xml, as the OpenSim
reproduction tabulates and builds it: github.com/RehabEngGroup/MBSbenchmarksInOpenSim,
help/benchmarks/A05_FlyballGovernor.rst and src/A05-FlyballGovernor/; Exudyn's model of the
IFToMM problem, TestModels/stiffFlyballGovernor.py, has the same geometry): gravity 9.81 along
-z; the shaft, 1 x 0.01 x 0.01 m, density 3000 kg/m^3 (0.3 kg), turns about the ground's z axis
at its lower end (the origin); the slider, a 0.1 m cube of the same density (3 kg), slides on
the shaft with it, its centre at height s = 0.5 m; two rods like the shaft hang from
A = (+0.05, 0, 1) and B = (-0.05, 0, 1) on the shaft (hinge axes normal to the shaft's x-z
plane), alpha = 30 degrees below the horizontal, each with a 5 kg point mass at its free end;
the rods' midpoints are joined to the slider's points (+-0.05, 0, s) by spring-dampers
k = 8e5 N/m, c = 4e4 N s/m, rest length 0.5 m (the springs' length at t = 0). At t = 0 the whole
assembly turns at 2 pi rad/s about z with no relative motion; the shaft is free (no drive).
10 s in 400 output steps (an assumption: the OpenSim reproduction reports 10 s).

Coordinates: phi (shaft), s (slider), theta1, theta2 (each rod's angle below the horizontal in
the shaft's frame). Lagrange's equations of T - V with Rayleigh's dissipation c/2 sum l_i'^2,
derived by SymPy and integrated by Radau (stiff: c/m ~ 1e4 1/s) at rtol 1e-12.
Self-checks: the angular momentum about z is conserved; energy + dissipated work is conserved
(the dissipated work integrated alongside); the two rods stay symmetric.

Body names (models/scenes/iftomm/A05_flyball_governor.toml): shaft, slider, rod1, rod2 (each
rod with its point mass: one body, centre of mass and inertia combined; points A or B at the
hinge, mid at the spring, ball at the point mass). Columns: slider.z (= s), shaft.wz,
rod1.x/y/z and rod2.x/y/z (combined centres of mass), rod1.ball.x/y/z, rod2.ball.x/y/z,
shaft.qw/qz.
Run: /usr/bin/python3 validation/references/iftomm/reference_A05.py  (writes A05_reference.csv)
"""
import sys

import numpy as np
import sympy as sp

import iftomm_common as ic

RHO, G = 3000.0, 9.81
M_BAR = RHO * 1.0 * 0.01 * 0.01          # shaft and each rod, 0.3 kg
M_SLIDER = RHO * 0.001                  # 3 kg (0.1 m cube)
M_BALL = 5.0
K, C, REST = 8e5, 4e4, 0.5
HINGE_X, HINGE_Z, HALF_SLIDER = 0.05, 1.0, 0.05
S0, ALPHA0, OMEGA0 = 0.5, np.radians(30.0), 2.0 * np.pi
T_END, STEPS = 10.0, 400
I_BAR = ic.box_inertia(M_BAR, 1.0, 0.01, 0.01)      # long along its own x
I_SHAFT = ic.box_inertia(M_BAR, 0.01, 0.01, 1.0)    # long along z
I_SLIDER = ic.box_inertia(M_SLIDER, 0.1, 0.1, 0.1)


def rod_combined():
    """Mass, distance of the centre of mass from the hinge, and principal inertia (rod frame,
    x along the rod) of a rod with its point mass: the values the scene lists."""
    m = M_BAR + M_BALL
    d = (M_BAR * 0.5 + M_BALL * 1.0) / m
    transverse = I_BAR[1] + M_BAR * (0.5 - d) ** 2 + M_BALL * (1.0 - d) ** 2
    return m, d, np.array([I_BAR[0], transverse, transverse])


def sym_rot(axis, a):
    c, s = sp.cos(a), sp.sin(a)
    if axis == "y":
        return sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def derive():
    """Lambdified M(q) and f(q, q') of M q'' = f, the spring rates and the energy terms."""
    q = sp.symbols("phi s th1 th2")
    qd = sp.symbols("dphi ds dth1 dth2")
    phi, s, th1, th2 = q
    rz = sym_rot("z", phi)

    def velocity(expr):
        return sp.Matrix([sum(sp.diff(e, qi) * qdi for qi, qdi in zip(q, qd)) for e in expr])

    def body_omega(r):
        rdot = r.applyfunc(lambda e: sum(sp.diff(e, qi) * qdi for qi, qdi in zip(q, qd)))
        w = r.T * rdot
        return sp.Matrix([w[2, 1], w[0, 2], w[1, 0]])

    t_kin, v_pot = 0, 0
    # shaft and slider turn with phi; their centres lie on the axis
    for mass, inertia, z in ((M_BAR, I_SHAFT, 0.5), (M_SLIDER, I_SLIDER, s)):
        w = body_omega(rz)
        x = sp.Matrix([0, 0, z])
        v = velocity(x)
        t_kin += mass * (v.T * v)[0] / 2 + sum(inertia[k] * w[k] ** 2 for k in range(3)) / 2
        v_pot += mass * G * z
    springs = []
    for sign, th, local in ((1, th1, sym_rot("y", th1)),
                            (-1, th2, sym_rot("z", sp.pi) * sym_rot("y", th2))):
        hinge = sp.Matrix([sign * HINGE_X, 0, HINGE_Z])
        r = rz * local
        w = body_omega(r)
        for mass, along in ((M_BAR, 0.5), (M_BALL, 1.0)):
            x = rz * (hinge + local * sp.Matrix([along, 0, 0]))
            v = velocity(x)
            t_kin += mass * (v.T * v)[0] / 2
            v_pot += mass * G * x[2]
        t_kin += sum(I_BAR[k] * w[k] ** 2 for k in range(3)) / 2
        gap = hinge + local * sp.Matrix([0.5, 0, 0]) - sp.Matrix([sign * HALF_SLIDER, 0, s])
        length = sp.sqrt((gap.T * gap)[0])
        springs.append(length)
        v_pot += K * (length - REST) ** 2 / 2
    rates = [sum(sp.diff(l, qi) * qdi for qi, qdi in zip(q, qd)) for l in springs]
    rayleigh = C * sum(r**2 for r in rates) / 2
    lag = t_kin - v_pot
    dl_dqd = [sp.diff(lag, v) for v in qd]
    mass = sp.Matrix([[sp.diff(p, v) for v in qd] for p in dl_dqd])
    f = sp.Matrix([sp.diff(lag, qi) - sum(sp.diff(p, qj) * vj for qj, vj in zip(q, qd))
                   - sp.diff(rayleigh, vi) for p, qi, vi in zip(dl_dqd, q, qd)])
    args = (q, qd)
    power = 2 * rayleigh
    return {
        "dmass": [sp.lambdify(args, mass.diff(qi), "numpy", cse=True) for qi in q],
        "df_dq": sp.lambdify(args, f.jacobian(q), "numpy", cse=True),
        "df_dqd": sp.lambdify(args, f.jacobian(qd), "numpy", cse=True),
        "dpower": sp.lambdify(args, [power.diff(v) for v in q + qd], "numpy", cse=True),
        "mass": sp.lambdify(args, mass, "numpy", cse=True),
        "force": sp.lambdify(args, f, "numpy", cse=True),
        "energy": sp.lambdify(args, t_kin + v_pot, "numpy", cse=True),
        "power": sp.lambdify(args, power, "numpy", cse=True),
        "momentum": sp.lambdify(args, dl_dqd[0], "numpy", cse=True),
        "lengths": sp.lambdify(args, springs, "numpy", cse=True),
    }


class Governor:
    def __init__(self):
        self.f = derive()

    def rhs(self, _t, y):
        q, qd = y[:4], y[4:8]
        acc = np.linalg.solve(np.array(self.f["mass"](q, qd), dtype=float),
                              np.array(self.f["force"](q, qd), dtype=float).ravel())
        return np.concatenate([qd, acc, [self.f["power"](q, qd)]])

    def jacobian(self, _t, y):
        """d rhs / d y, exact: d(M^-1 f)/dq = M^-1 (df/dq - dM/dq_i M^-1 f)."""
        q, qd = y[:4], y[4:8]
        m = np.array(self.f["mass"](q, qd), dtype=float)
        acc = np.linalg.solve(m, np.array(self.f["force"](q, qd), dtype=float).ravel())
        dm_acc = np.column_stack([np.array(d(q, qd), dtype=float) @ acc for d in self.f["dmass"]])
        jac = np.zeros((9, 9))
        jac[:4, 4:8] = np.eye(4)
        jac[4:8, :4] = np.linalg.solve(m, np.array(self.f["df_dq"](q, qd), dtype=float) - dm_acc)
        jac[4:8, 4:8] = np.linalg.solve(m, np.array(self.f["df_dqd"](q, qd), dtype=float))
        jac[8, :8] = np.array(self.f["dpower"](q, qd), dtype=float)
        return jac


def columns(y):
    m_rod, d_rod, _ = rod_combined()
    phi, s, th1, th2, dphi = y[:, 0], y[:, 1], y[:, 2], y[:, 3], y[:, 4]
    cols = {"slider.z": s, "shaft.wz": dphi, "shaft.qw": np.cos(phi / 2.0),
            "shaft.qz": np.sin(phi / 2.0)}
    for name, sign, th in (("rod1", 1.0, th1), ("rod2", -1.0, th2)):
        for label, along in (("", d_rod), (".ball", 1.0)):
            radial = sign * (HINGE_X + along * np.cos(th))
            cols[f"{name}{label}.x"] = radial * np.cos(phi)
            cols[f"{name}{label}.y"] = radial * np.sin(phi)
            cols[f"{name}{label}.z"] = HINGE_Z - along * np.sin(th)
    return cols


def compute(t_end=T_END):
    t = np.linspace(0.0, t_end, int(round(t_end / T_END * STEPS)) + 1)
    model = Governor()
    y0 = np.array([0.0, S0, ALPHA0, ALPHA0, OMEGA0, 0.0, 0.0, 0.0, 0.0])
    y, sol = ic.integrate(model.rhs, y0, t, method="Radau", jac=model.jacobian)
    q, qd = y[:, :4].T, y[:, 4:8].T
    energy = model.f["energy"](q, qd) + y[:, 8]
    momentum = model.f["momentum"](q, qd)
    lengths = np.array(model.f["lengths"](y0[:4], y0[4:8]), dtype=float)
    e_scale = model.f["energy"](y0[:4], y0[4:8])
    checks = [
        ("angular momentum about z drift, relative", ic.relative_drift(momentum, momentum[0]),
         1e-10, "conserved; 100 rtol"),
        ("(energy + dissipated work) drift / E(0)", ic.relative_drift(energy, e_scale), 1e-9,
         "conserved; the dissipated work is a quadrature of c l'^2 with l' ~ 1e-2: 1000 rtol"),
        ("max |theta1 - theta2| (rad)", np.max(np.abs(y[:, 2] - y[:, 3])), 1e-10,
         "symmetric start stays symmetric: 100 rtol"),
        ("spring length at t = 0 - rest length (m)", float(np.max(np.abs(lengths - REST))), 1e-15,
         "the data's geometry: the springs start unstretched (roundoff)"),
    ]
    m_rod, d_rod, i_rod = rod_combined()
    title = (f"A05 flyball governor: {len(t)} rows to {t_end} s, {sol.nfev} evaluations; "
             f"s in [{y[:, 1].min():.9f}, {y[:, 1].max():.9f}] m, s({t_end}) = {y[-1, 1]:.12f}, "
             f"shaft rate {y[-1, 4]:.9f} rad/s at the end, dissipated {y[-1, 8]:.6e} J; "
             f"rod + ball: {m_rod} kg, centre {d_rod!r} m from the hinge, inertia {list(i_rod)}")
    return t, columns(y), checks, title


def main(out_dir=ic.HERE):
    t, cols, checks, title = compute()
    ic.write_csv("A05_reference.csv", t, cols, out_dir)
    return ic.report(title, checks)


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
