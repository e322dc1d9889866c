"""The IFToMM benchmark scenes under every scheme that holds them (validation/iftomm/README.md),
ctest `validation/iftomm_schemes` (label validation; CONDYN_BINARY names the command): each
(scene, scheme) pair below, over a duration short enough for the tier, stays within TOLERANCE of
the scene's independent reference; and A03 as rigid bodies agrees with the built-in Andrews
model over its whole run."""
import os
import tempfile

import pytest

import andrews_agreement as aa
import runs as ir

CONDYN = os.environ.get("CONDYN_BINARY", os.path.join(ir.ROOT, "build", "condyn"))
# Every scene runs at rtol = 1e-10 (its own [solve]). The validation suite's bound on a run's
# global error (docs/validation.md): 1000 x rtol of the quantity's scale, here each scene's size,
# 1 m (1 rad for A03's angles, whose scale is at least 1 rad): IDA and CVODE control the local
# error, which builds up over about 10^3 steps.
RTOL = 1e-10
TOLERANCE = 1000 * RTOL * 1.0

# (scene, t_end: its own when None, schemes). Durations cut to keep the tier under 20 s of CPU
# (about 8 s); a scheme left out of a scene misses the bound over this duration (the table in
# docs/validation.md has every pair over the full duration). Observed errors / TOLERANCE, the
# largest per scene: inclined_revolute 0.58 (baumgarte), A03 0.68 (baumgarte), heavy_top 0.46
# (projection), A01 0.76 (baumgarte), A02 0.19 (index3), A04 0.082 (elimination), A05 0.39
# (elimination).
HOLDS = [
    ("inclined_revolute", None, ["index1", "baumgarte", "ggl", "index2", "projection"]),
    ("A03", None, ["index1", "baumgarte", "ggl", "index2"]),
    ("heavy_top", 1.0, ["index1", "baumgarte", "ggl", "index2", "projection"]),
    ("A01", 20.0, ["baumgarte", "ggl"]),  # 8.4 periods; index1, index2, projection: 5e-7
    # before the first singular passage (0.70 to 0.75 s), every scheme
    ("A02", 0.25, ["elimination", "index1", "baumgarte", "ggl", "index2", "index3",
                   "projection"]),
    ("A04", 2.0, ["elimination", "index1", "baumgarte", "ggl", "index2", "projection"]),
    ("A05", 2.5, ["elimination", "index1", "baumgarte", "ggl", "index2", "projection"]),
]
PAIRS = [(key, t_end, scheme) for key, t_end, schemes in HOLDS for scheme in schemes]


@pytest.fixture(scope="module")
def work_dir():
    with tempfile.TemporaryDirectory() as d:
        yield d


@pytest.mark.parametrize("key,t_end,scheme", PAIRS, ids=[f"{k}-{s}" for k, _, s in PAIRS])
def test_scheme_stays_within_tolerance_of_the_reference(work_dir, key, t_end, scheme):
    run = ir.run_scheme(CONDYN, ir.benchmark(key), scheme, work_dir, t_end,
                        ["--max-steps", "200000"])
    assert run.status == "finished", f"{key} under {scheme}: {run.status}: {run.message}"
    assert run.t_reached == pytest.approx(run.t_end)
    assert run.error <= TOLERANCE, (
        f"{key} under {scheme}: {ir.benchmark(key).what} off by {run.error:.3e} from the "
        f"reference, beyond {TOLERANCE:.0e} (1000 rtol)")


def test_andrews_as_rigid_bodies_agrees_with_the_built_in_model(work_dir):
    t, builtin, multibody = aa.run_both(CONDYN, work_dir, "ggl", RTOL)
    assert t[-1] == pytest.approx(0.03)
    for body, diff in aa.differences(builtin, multibody).items():
        worst, bound = float(abs(diff).max()), aa.agreement_bound(builtin, body, RTOL)
        assert worst <= bound, f"{body}: the scene's angle is {worst:.3e} rad off the built-in's"
