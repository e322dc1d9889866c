#!/usr/bin/python3
"""IFToMM A02, the N-four-bar mechanism (N = 40), in its one minimal coordinate.

Specification (http://lim.ii.udc.es/mbsbenchmark/dist/A02/A02_specification.xml): 2N+1 links of
1 m with a uniformly distributed mass of 1 kg, gravity 9.81 N/kg along -y, N = 40, 20 s sampled
in 400 output steps; initially in the figure's position (the N+1 cranks upright on the ground
pivots A_i = (i, 0), the N couplers horizontal at y = 1, as the OpenSim reproduction builds it:
github.com/RehabEngGroup/MBSbenchmarksInOpenSim, src/A02-NFourBarMechanism/createModel.cpp) with
B0 moving at +1 m/s along x. Reference: position and velocity of B0 (the tip of crank 0).

On the parallelogram branch every crank turns by the same angle phi (from +x; phi(0) = pi/2,
phi'(0) = -1 so that B0 moves along +x) and every coupler translates with the cranks' tips:
  T = (1/2) [(N+1) m L^2 / 3 + N m L^2] phi'^2,  V = [(N+1)/2 + N] m g L sin phi,
a pendulum equation phi'' = -(V'/m_eff). The mechanism turns for good: each time phi passes
0 or pi (mod 2 pi) every link lies on the ground line and the Jacobian loses rank (N+1 DOF);
this reference stays on the branch where the couplers keep translating, which is the branch the
specification's reference follows, as a smooth solution through every such passage.

Body names (as in models/scenes/iftomm/A02_n_four_bar.toml): crank0 ... crank40 (points A at
the pivot, B at the tip; body frame along the crank, angle = phi), coupler1 ... coupler40
(coupler i joins B_{i-1} to B_i; angle 0). Columns: crank0 and crank40, coupler1 and coupler40,
B0 = crank0.B; B0's velocity is coupler1's (it translates with B0).
Self-checks: energy conserved, the time of one turn against the quadrature
T = integral over one turn of d phi / |phi'(phi)|.
Run: /usr/bin/python3 validation/references/iftomm/reference_A02.py  (writes A02_reference.csv)
"""
import sys

import numpy as np
from scipy.integrate import quad

import iftomm_common as ic

N, MASS, LENGTH, G = 40, 1.0, 1.0, 9.81
PHI0, PHI_DOT0 = np.pi / 2.0, -1.0
T_END, STEPS = 20.0, 400
M_EFF = ((N + 1) / 3.0 + N) * MASS * LENGTH**2
V_COEF = ((N + 1) / 2.0 + N) * MASS * G * LENGTH


def rhs(_t, y):
    return [y[1], -V_COEF * np.cos(y[0]) / M_EFF]


def energy(phi, phi_dot):
    return 0.5 * M_EFF * phi_dot**2 + V_COEF * np.sin(phi)


def one_turn(_t, y):
    """Zero each time phi = pi/2 (mod 2 pi): B0 upright again."""
    return np.sin((y[0] - PHI0) / 2.0)


def body_columns(phi, phi_dot):
    c, s = np.cos(phi), np.sin(phi)
    cols = {}
    for i in (0, N):
        cols[f"crank{i}.x"] = i + 0.5 * LENGTH * c
        cols[f"crank{i}.y"] = 0.5 * LENGTH * s
        cols[f"crank{i}.angle"] = phi
        cols[f"crank{i}.omega"] = phi_dot
    cols["crank0.B.x"] = LENGTH * c
    cols["crank0.B.y"] = LENGTH * s
    for i in (1, N):
        cols[f"coupler{i}.x"] = i - 0.5 + LENGTH * c
        cols[f"coupler{i}.y"] = LENGTH * s
        cols[f"coupler{i}.angle"] = np.zeros_like(phi)
        cols[f"coupler{i}.vx"] = -LENGTH * s * phi_dot
        cols[f"coupler{i}.vy"] = LENGTH * c * phi_dot
    return cols


def compute(t_end=T_END):
    t = np.linspace(0.0, t_end, int(round(t_end / T_END * STEPS)) + 1)
    y, sol = ic.integrate(rhs, [PHI0, PHI_DOT0], t, events=one_turn)
    phi, phi_dot = y[:, 0], y[:, 1]
    e0 = energy(PHI0, PHI_DOT0)
    turn, _ = quad(lambda p: 1.0 / np.sqrt(2.0 * (e0 - V_COEF * np.sin(p)) / M_EFF),
                   0.0, 2.0 * np.pi, epsabs=0.0, epsrel=1e-13, limit=200)
    turns = sol.t_events[0][sol.t_events[0] > 1e-9]
    passages = np.floor(-(phi - PHI0) / (np.pi / 2.0))  # quarter turns from upright
    checks = [
        ("energy drift / (m_eff phi'(0)^2 / 2 + V_coef)",
         ic.relative_drift(energy(phi, phi_dot), 0.5 * M_EFF + V_COEF), 1e-10,
         "conserved; 100 rtol"),
        ("max |t_turn,i+1 - t_turn,i - T_quadrature| / T",
         np.max(np.abs(np.diff(np.concatenate([[0.0], turns])) - turn)) / turn, 1e-10,
         "100 rtol"),
    ]
    title = (f"A02 N-four-bar, N = {N}: {len(t)} rows to {t_end} s, one turn {turn:.12f} s "
             f"(quadrature), {len(turns)} turns, {int(passages[-1] // 2)} horizontal passages "
             f"(singular positions)")
    return t, body_columns(phi, phi_dot), checks, title


def main(out_dir=ic.HERE):
    t, columns, checks, title = compute()
    ic.write_csv("A02_reference.csv", t, columns, out_dir)
    return ic.report(title, checks)


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
