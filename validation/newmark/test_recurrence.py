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
    # The reactions: lambda at each row from acceleration level, [M A^T; A 0] [u''; lambda] =
    # [f - C v - K u; 0], on either side's u and v: a linear function of them, so they differ by
    # at most the norms of K and C times the bounds above (observed 60 eps of the peak reaction,
    # 3e-9 N of 2.3e5 N, 1e-4 of the bound).
    norm_k = float(np.max(np.sum(np.abs(frame.K), axis=1)))
    norm_c = float(np.max(np.sum(np.abs(frame.C), axis=1)))
    bound = steps * EPS * (norm_k * u_peak + norm_c * v_peak)
    assert r_diff <= bound, f"reactions differ by {r_diff:.3e} (peak {r_peak:.3e})"
