"""Writes the ten synthetic accelerograms of the IDA example (records/syn01.csv ... syn10.csv),
each in g at dt = 0.02 s over 20 s: white noise (a seeded normal sequence, seed k for record k)
filtered by a Kanai-Tajimi ground (omega_g = 5 pi rad/s, zeta_g = 0.6: a firm soil), times the
Jennings, Housner and Tsai envelope (a quadratic rise to 2 s, strong motion to 8 s, an
exponential decay after), ending at rest (the last sample 0: a table holds its last value after
it), its peak |a| scaled to 0.3 g. The same script writes the same files on any machine.

    /usr/bin/python3 models/scenes/ida/make_records.py
    build/condyn sweep models/scenes/ida/frame_ida.toml
"""

import os

import numpy as np
from scipy import signal

DT, DURATION, PGA_G = 0.02, 20.0, 0.3
OMEGA_G, ZETA_G = 5.0 * np.pi, 0.6


def envelope(t):
    """Jennings, Housner and Tsai (1968): (t/2)^2 to 2 s, 1 to 8 s, exp(-0.4 (t - 8)) after."""
    return np.where(t < 2.0, (t / 2.0) ** 2, np.where(t <= 8.0, 1.0, np.exp(-0.4 * (t - 8.0))))


def record(seed):
    t = np.arange(0.0, DURATION + DT / 2, DT)
    noise = np.random.default_rng(seed).standard_normal(len(t))
    # The Kanai-Tajimi filter's absolute acceleration:
    # (2 zeta w s + w^2) / (s^2 + 2 zeta w s + w^2).
    ground = signal.lti([2 * ZETA_G * OMEGA_G, OMEGA_G ** 2],
                        [1.0, 2 * ZETA_G * OMEGA_G, OMEGA_G ** 2])
    _, a, _ = signal.lsim(ground, noise, t)
    a = a * envelope(t)
    a[-1] = 0.0
    return t, a * (PGA_G / np.max(np.abs(a)))


def main():
    folder = os.path.join(os.path.dirname(os.path.abspath(__file__)), "records")
    os.makedirs(folder, exist_ok=True)
    for k in range(1, 11):
        t, a = record(k)
        with open(os.path.join(folder, f"syn{k:02d}.csv"), "w") as f:
            f.write(f"# Synthetic accelerogram {k} of 10 in g (models/scenes/ida/make_records.py, "
                    f"seed {k}): filtered white noise, enveloped, peak {PGA_G} g\n")
            f.write("t,acceleration_g\n")
            for ti, ai in zip(t, a):
                f.write(f"{ti:.2f},{ai:.6f}\n")


if __name__ == "__main__":
    main()
