"""ctest `validation/newmark_recurrence` (label validation; CONDYN_BINARY names the command): the
El Centro shear frame under `condyn run --scheme newmark --step h` equals the numpy Newmark
recurrence of recurrence.py, written independently of condyn, to roundoff (issue 45, "Done
when"; docs/validation.md "Newmark against a numpy recurrence")."""
import os
import tempfile

import numpy as np
import pytest

import recurrence as nr

CONDYN = os.environ.get("CONDYN_BINARY", os.path.join(nr.ROOT, "build", "condyn"))
EPS = np.finfo(float).eps
BETA = 0.25  # average acceleration, condyn's default for scheme = "newmark"


@pytest.fixture(scope="module")
def frame():
    return nr.ShearFrame()


# h = 0.02 is the record's own spacing (what another program is run with); h = 0.01 halves it.
@pytest.mark.parametrize("h", [0.02, 0.01])
def test_condyn_newmark_equals_the_numpy_recurrence(frame, h):
    with tempfile.TemporaryDirectory() as work_dir:
        d = nr.differences(frame, nr.condyn_run(CONDYN, frame, h, work_dir), h)
    steps = d["steps"]
    assert steps == round(frame.solve["t_end"] / h)
    u_diff, u_peak = d["u"]
    v_diff, v_peak = d["v"]
    r_diff, r_peak = d["f_con"]
    assert u_peak > 1e-2 and r_peak > 1e5  # the frame moves (cm) and its floors carry force (N)
    # u and v: both sides solve one well-conditioned linear system per step, so they differ by
    # the roundoff of a step, eps of the response, accumulated at most linearly over a stable
    # recurrence: steps x eps x peak (observed 3 to 4 eps of the peak in u, 28 to 42 eps in v,
    # against 1558 and 3116 eps).
    assert u_diff <= steps * EPS * u_peak
    assert v_diff <= steps * EPS * v_peak
    # The reactions: the constraint modes of index-3 average acceleration have amplification
    # factor -1 (gamma = 1/2 damps nothing), so each step's roundoff in A u and A v (eps |u|,
    # eps |v|) enters the multipliers as m / (beta h^2) and m gamma / (beta h) times itself and
    # is kept, alternating in sign: both sides carry such a sum, bounded by steps x eps x
    # m (u_peak / (beta h^2) + gamma v_peak / (beta h)); 16 times it (observed 3.5 times at
    # h = 0.02, 1.7 at 0.01; 2e-9 of the peak reaction at h = 0.01).
    m = float(np.max(np.diag(frame.M)))
    kick = m * (u_peak / (BETA * h * h) + 0.5 * v_peak / (BETA * h))
    assert r_diff <= 16 * steps * EPS * kick, f"reactions differ by {r_diff:.3e} (peak {r_peak:.3e})"
