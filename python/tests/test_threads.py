"""The GIL is released while integrating: two scenes run in two threads overlap in time, give
the results they give alone, and the main thread keeps running Python meanwhile."""

import threading
import time

import numpy as np
import scipy.sparse as sp

import condyn


def long_chain(scheme):
    """A chain of 300 masses whose run takes a few tenths of a second."""
    n = 300
    k = sp.diags([np.full(n - 1, -1e4), np.full(n, 2e4), np.full(n - 1, -1e4)], [-1, 0, 1],
                 format="csr")
    a = sp.csr_matrix(([1.0, -1.0], ([0, 0], [9, n - 10])), shape=(1, n))
    f = np.zeros(n)
    f[-1] = 1.0
    return {"model": {"type": "matrix", "mass": sp.identity(n, format="csr"), "stiffness": k},
            "constraint_block": [{"file": a}],
            "load": [{"pattern": f, "value": {"type": "harmonic", "amplitude": 1.0,
                                                "omega": 7.0}}],
            "solve": {"t_end": 4.0, "output_step": 0.1, "scheme": scheme, "rtol": 1e-9}}


def test_two_threads_overlap_and_match_sequential_runs():
    scenes = {"ggl": long_chain("ggl"), "index1": long_chain("index1")}
    alone = {s: condyn.run(scene) for s, scene in scenes.items()}
    spans, results = {}, {}

    def work(scheme):
        start = time.perf_counter()
        results[scheme] = condyn.run(scenes[scheme])
        spans[scheme] = (start, time.perf_counter())

    threads = [threading.Thread(target=work, args=(s,)) for s in scenes]
    ticks = 0
    for t in threads:
        t.start()
    while any(t.is_alive() for t in threads):
        ticks += 1  # Python in the main thread while both integrate
        time.sleep(0.001)
    for t in threads:
        t.join()
    for s in scenes:
        np.testing.assert_array_equal(results[s].u, alone[s].u)
    (s1, e1), (s2, e2) = spans.values()
    overlap = min(e1, e2) - max(s1, s2)
    shorter = min(e1 - s1, e2 - s2)
    assert shorter > 0.05, f"runs too short to show overlap: {shorter:.3f} s"
    assert overlap > 0.5 * shorter, f"overlap {overlap:.3f} s of {shorter:.3f} s"
    # With the GIL held, the main thread could not run at all while a run integrates.
    assert ticks >= 10, f"the main thread ran only {ticks} times"
