"""condyn.sweep (docs/sweep.md, issue 46): the sweep file's refusals, the product of its axes and
the run keys, and sweeps run on a real two-worker Dask cluster (one for the module, reached
through its scheduler's address as --scheduler would): peaks against condyn.run, a failed run's
row, restart skipping the runs done, the same table twice, results.h5 beside results.csv, the
[[check]] verdicts against condyn.check, each run's kept result against condyn run's HDF5, the IDA
example; and a dask-scheduler with two dask-worker processes started by hand, one killed
mid-sweep."""

import csv
import json
import math
import os
import re
import shutil
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import condyn
from condyn.sweep_file import expand, map_files, read_sweep

distributed = pytest.importorskip("distributed")
# Debian's distributed 2022.12 starts its event loop in a way tornado 6.2 calls deprecated.
pytestmark = pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")

SCENE = """\
name = "two storeys under a recorded ground motion"
[model]
type = "matrix"
dofs = ["u1", "u2"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[200.0, -100.0], [-100.0, 100.0]]
damping = { rayleigh = [0.1, 0.001] }
[ground_motion]
acceleration = { type = "table", file = "records/a.csv", scale = 1.0 }
influence = { u1 = 1.0, u2 = 1.0 }
[solve]
t_end = 1.0
output_step = 0.05
rtol = 1e-6
atol = 1e-9
[output]
quantities = ["displacement", "reaction", "drift"]
"""

SWEEP = """\
scene = "frame.toml"
[[axis]]
key = "ground_motion.acceleration.file"
values = ["records/a.csv", "records/b.csv"]
[[axis]]
key = "ground_motion.acceleration.scale"
values = [0.5, 1.0, 2.0]
[keep]
peaks = ["u2", "reaction_u1"]
"""


def write_record(path, omega):
    """A ground acceleration sin(omega t) sampled every 0.01 s over 1 s."""
    t = np.arange(0.0, 1.0 + 1e-9, 0.01)
    np.savetxt(path, np.column_stack([t, np.sin(omega * t)]), delimiter=",", header="t,a",
               comments="")


@pytest.fixture
def study(tmp_path):
    """A folder with the scene, two records and the sweep file; returns the sweep file's path."""
    (tmp_path / "records").mkdir()
    write_record(tmp_path / "records" / "a.csv", 10.0)
    write_record(tmp_path / "records" / "b.csv", 14.0)
    (tmp_path / "frame.toml").write_text(SCENE)
    (tmp_path / "study.toml").write_text(SWEEP)
    return tmp_path / "study.toml"


@pytest.fixture(scope="module")
def scheduler():
    """A real cluster of two worker processes for the module's sweeps: its scheduler's address."""
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        yield cluster.scheduler_address


def read_table(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def without_wall(header, rows):
    j = header.index("wall_s")
    return [r[:j] + r[j + 1:] for r in rows]


# --- the sweep file ------------------------------------------------------------------------------

@pytest.mark.parametrize("edit, key, problem", [
    (lambda s: "workers = 2\n" + s, "workers", "unknown key"),
    (lambda s: s.replace('scene = "frame.toml"', 'scene = "nowhere.toml"'), "scene",
     "no such file"),
    (lambda s: s.replace("values = [0.5, 1.0, 2.0]", "values = []"), "axis[2].values",
     "non-empty list"),
    (lambda s: s.replace("values = [0.5, 1.0, 2.0]", "values = [0.5, 1.0, 0.5]"),
     "axis[2].values", "0.5 is listed twice"),
    (lambda s: s.replace('key = "ground_motion.acceleration.scale"', 'kee = "x"'),
     "axis[2].kee", "unknown key"),
    (lambda s: s.replace("ground_motion.acceleration.scale", "ground_motions.acceleration.scale"),
     "axis[2].key", "it has no 'ground_motions'"),
    (lambda s: s.replace("ground_motion.acceleration.scale", "load[1].value"),
     "axis[2].key", "it has no 'load'"),
    (lambda s: s.replace("ground_motion.acceleration.scale", "solve..rtol"),
     "axis[2].key", "not a dotted scene path"),
    (lambda s: s.replace("ground_motion.acceleration.scale", "ground_motion.acceleration.file"),
     "axis[2].key", "swept by an earlier axis"),
    # keys the scene parser refuses: an unknown leaf, a value of the wrong type, a missing file
    (lambda s: s.replace("ground_motion.acceleration.scale", "solve.rtoll"),
     "axis[2] (solve.rtoll = 0.5)", "solve.rtoll: unknown key"),
    (lambda s: s.replace("values = [0.5, 1.0, 2.0]", 'values = [0.5, "big"]'),
     'axis[2] (ground_motion.acceleration.scale = "big")', "scale"),
    (lambda s: s.replace('"records/b.csv"', '"records/c.csv"'),
     'axis[1] (ground_motion.acceleration.file = "records/c.csv")', "records/c.csv"),
    (lambda s: s.replace('peaks = ["u2", "reaction_u1"]', 'peaks = "u2"'), "keep.peaks",
     "expected a list"),
    (lambda s: s.replace("[keep]", "[keep]\npeak = 1"), "keep.peak", "unknown key"),
    (lambda s: s.replace("[[axis]]", "[[axis]\n", 1), "", "not valid TOML"),
])
def test_a_bad_sweep_file_is_refused_before_any_run_naming_file_and_key(study, edit, key,
                                                                       problem):
    study.write_text(edit(SWEEP))
    with pytest.raises(condyn.SweepError) as e:
        condyn.sweep(study, workers=1, progress=False)
    message = str(e.value)
    assert message.startswith(f"{study}: {key}"), message
    assert problem in message, message
    assert not (study.parent / "study").exists()  # no results folder: nothing ran


def test_the_runs_are_the_product_of_the_axes_each_keyed_by_its_inputs(study):
    runs = expand(read_sweep(study))
    assert [r.values for r in runs] == [(f, s) for f in ("records/a.csv", "records/b.csv")
                                        for s in (0.5, 1.0, 2.0)]
    assert len({r.key for r in runs}) == 6
    assert runs[4].scene["ground_motion"]["acceleration"] == {
        "type": "table", "file": "records/b.csv", "scale": 1.0}
    assert [r.key for r in expand(read_sweep(study))] == [r.key for r in runs]  # read again
    # A record's content is an input: an edited b.csv changes the keys of its three runs only.
    write_record(study.parent / "records" / "b.csv", 15.0)
    again = expand(read_sweep(study))
    assert [a.key == b.key for a, b in zip(runs, again)] == [True] * 3 + [False] * 3


# --- sweeps on the cluster -----------------------------------------------------------------------

def test_peaks_equal_condyn_run_of_each_scene_and_results_h5_holds_the_table(study, scheduler):
    summary = condyn.sweep(study, scheduler=scheduler, progress=False)
    assert summary == {"runs": 6, "ok": 6, "failed": {}, "skipped": 0, "missing": 0,
                       "table": str(study.parent / "study" / "results.csv")}
    header, rows = read_table(summary["table"])
    assert header == ["run", "ground_motion.acceleration.file",
                      "ground_motion.acceleration.scale", "status", "steps", "wall_s", "peak_u2",
                      "peak_time_u2", "peak_reaction_u1", "peak_time_reaction_u1"]
    for run, row in zip(expand(read_sweep(study)), rows):
        scene = dict(run.scene)
        scene["ground_motion"] = {**scene["ground_motion"], "acceleration": {
            **scene["ground_motion"]["acceleration"], "file": str(study.parent / run.values[0])}}
        r = condyn.run(scene)  # the same run in this process: deterministic, so bit for bit
        cells = dict(zip(header, row))
        assert cells["run"] == run.key and cells["ground_motion.acceleration.scale"] == \
            repr(run.values[1])
        assert cells["status"] == "ok" and int(cells["steps"]) == r.summary["steps"]
        for column, values in (("u2", r.u[:, 1]), ("reaction_u1", r.reaction[:, 0])):
            i = int(np.argmax(np.abs(values)))
            assert float(cells[f"peak_{column}"]) == abs(values[i])
            assert float(cells[f"peak_time_{column}"]) == r.t[i]
    h5py = pytest.importorskip("h5py")
    with h5py.File(study.parent / "study" / "results.h5", "r") as f:
        assert list(f.attrs["columns"]) == header
        assert list(f["run"].asstr()[()]) == [r[0] for r in rows]
        np.testing.assert_array_equal(f["peak_u2"][()], [float(r[6]) for r in rows])


def test_a_failed_run_is_a_row_with_its_failure_kind(study, scheduler):
    study.write_text(SWEEP + '[[axis]]\nkey = "solve.max_steps"\nvalues = [100000, 5]\n')
    summary = condyn.sweep(study, scheduler=scheduler, progress=False)
    assert summary["runs"] == 12 and summary["ok"] == 6
    assert summary["failed"] == {"step_budget": 6}
    header, rows = read_table(summary["table"])
    table = [dict(zip(header, row)) for row in rows]
    fewest_ok = min(int(c["steps"]) for c in table if c["status"] == "ok")
    for cells in table:
        assert cells["status"] == ("ok" if cells["solve.max_steps"] == "100000" else
                                   "step_budget")
        if cells["status"] != "ok":  # a failed run keeps no peaks: its rows stop early
            assert cells["peak_u2"] == "" and 0 < int(cells["steps"]) < fewest_ok


def test_restart_runs_only_what_is_missing_and_the_same_sweep_gives_the_same_table(
        study, scheduler):
    first = condyn.sweep(study, scheduler=scheduler, out=study.parent / "one", progress=False)
    header, rows = read_table(first["table"])
    # A sweep stopped after two rows, the third cut short as it was written.
    shutil.copytree(study.parent / "one", study.parent / "two")
    with open(study.parent / "two" / "results.csv", "w", newline="") as f:
        f.write(",".join(header) + "\n" + "".join(",".join(r) + "\n" for r in rows[:2]))
        f.write(",".join(rows[2])[:10])
    again = condyn.sweep(study, scheduler=scheduler, out=study.parent / "two", progress=False)
    assert again["skipped"] == 2 and again["ok"] == 6 and again["missing"] == 0
    header2, rows2 = read_table(again["table"])
    assert header2 == header
    # The two rows kept are the first sweep's own (wall_s included); the others equal but wall_s.
    assert rows2[:2] == rows[:2]
    assert without_wall(header, rows2) == without_wall(header, rows)
    # Nothing left to do: no run, the table unchanged.
    text = (study.parent / "two" / "results.csv").read_text()
    third = condyn.sweep(study, scheduler=scheduler, out=study.parent / "two", progress=False)
    assert third["skipped"] == 6 and (study.parent / "two" / "results.csv").read_text() == text


def test_a_kept_column_no_run_has_stops_the_sweep_naming_it(study, scheduler):
    study.write_text(SWEEP.replace('"reaction_u1"', '"u9"'))
    with pytest.raises(condyn.SweepError, match=r"keep\.peaks: no column 'u9' .*columns: t, u1"):
        condyn.sweep(study, scheduler=scheduler, progress=False)
    _, rows = read_table(study.parent / "study" / "results.csv")
    assert rows == []


def test_a_table_of_another_sweep_is_refused(study, scheduler):
    out = study.parent / "study"
    out.mkdir()
    (out / "results.csv").write_text("run,status\nabc,ok\n")
    with pytest.raises(condyn.SweepError, match="written by another sweep"):
        condyn.sweep(study, scheduler=scheduler, progress=False)
    assert (out / "results.csv").read_text() == "run,status\nabc,ok\n"


CHECKS = """\
[[check]]
quantity = "u2"
max_abs = 0.03
[[check]]
quantity = "drift_position"
max_abs = 1e-9
[[check]]
quantity = "u2"
reference = { file = "records/rest.csv" }
tolerance = 0.03
"""


def scene_of(study, run):
    """The run's scene as condyn.run takes it in this process: its record by an absolute path."""
    return map_files(run.scene, lambda name: str(study.parent / name))


def test_check_verdicts_are_columns_equal_to_condyn_check_and_counted(study, scheduler):
    # u2's peak is 0.011 to 0.096 over the six runs: a bound of 0.03 holds in some, not others;
    # the run with max_steps = 5 fails, and its checks are not evaluated (empty cells). check[3]
    # holds u2 against a file (zeros at three times), which travels to the workers with the task.
    (study.parent / "frame.toml").write_text(SCENE + CHECKS)
    (study.parent / "records" / "rest.csv").write_text("t,u2\n0,0\n0.5,0\n1,0\n")
    study.write_text(SWEEP + '[[axis]]\nkey = "solve.max_steps"\nvalues = [100000, 5]\n')
    summary = condyn.sweep(study, scheduler=scheduler, progress=False)
    header, rows = read_table(summary["table"])
    assert header[header.index("peak_time_reaction_u1") + 1:] == [
        "checks_passed", "check1_passed", "check1_computed", "check2_passed", "check2_computed",
        "check3_passed", "check3_computed"]
    passed = failed = 0
    failed_each = {}
    for run, row in zip(expand(read_sweep(study)), rows):
        cells = dict(zip(header, row))
        if cells["status"] != "ok":
            assert [cells[c] for c in header[-7:]] == [""] * 7
            continue
        verdict = condyn.check(scene_of(study, run))  # the same run here: bit for bit
        for k, c in enumerate(verdict["checks"], start=1):
            assert cells[f"check{k}_passed"] == ("true" if c["passed"] else "false")
            assert float(cells[f"check{k}_computed"]) == c["computed"]
        assert cells["checks_passed"] == ("true" if verdict["passed"] else "false")
        # check[1] is max |u2| over the output rows: the kept peak itself.
        assert float(cells["check1_computed"]) == float(cells["peak_u2"])
        passed += verdict["passed"]
        failed += not verdict["passed"]
        for k, c in enumerate(verdict["checks"], start=1):
            if not c["passed"]:
                failed_each[f"check{k}"] = failed_each.get(f"check{k}", 0) + 1
    assert passed > 0 and failed > 0  # the study has both verdicts
    assert summary["checks"] == {"passed": passed, "failed": failed,
                                 "failed_by_check": failed_each}
    h5py = pytest.importorskip("h5py")
    with h5py.File(study.parent / "study" / "results.h5", "r") as f:  # true/false as 1/0
        expected = [{"true": 1.0, "false": 0.0, "": math.nan}[r[header.index("checks_passed")]]
                    for r in rows]
        np.testing.assert_array_equal(f["checks_passed"][()], expected)


def test_an_axis_that_changes_the_number_of_checks_is_refused(study):
    (study.parent / "frame.toml").write_text(SCENE + CHECKS)
    (study.parent / "records" / "rest.csv").write_text("t,u2\n0,0\n1,0\n")
    one = '{ quantity = "u2", max_abs = 1.0 }'
    study.write_text(SWEEP + f'[[axis]]\nkey = "check"\nvalues = [[{one}], [{one}, {one}]]\n')
    with pytest.raises(condyn.SweepError, match=r"has 1 \[\[check\]\] tables where the scene "
                       r"has 3"):
        condyn.sweep(study, workers=1, progress=False)
    assert not (study.parent / "study").exists()


def test_kept_results_are_the_files_condyn_run_writes_brought_back_by_key(study, scheduler, cli):
    h5py = pytest.importorskip("h5py")
    scene = SCENE  # its [output] quantities, and only those, are in the file
    study.write_text(SWEEP.replace("[keep]", "[keep]\nresults = true"))
    summary = condyn.sweep(study, scheduler=scheduler, progress=False)
    runs = expand(read_sweep(study))
    folder = study.parent / "study" / "runs"
    assert sorted(os.listdir(folder)) == sorted(f"{r.key}.h5" for r in runs)
    for run in runs:  # each equals `condyn run --out` of the run's scene, bit for bit
        (study.parent / "one.toml").write_text(scene.replace(
            "records/a.csv", run.values[0]).replace("scale = 1.0", f"scale = {run.values[1]!r}"))
        out = study.parent / f"run{run.index}.h5"
        subprocess.run([str(cli), "run", str(study.parent / "one.toml"), "--out", str(out)],
                       check=True, capture_output=True)
        with h5py.File(folder / f"{run.key}.h5", "r") as kept, h5py.File(out, "r") as ran:
            assert dict(kept.attrs) == dict(ran.attrs)
            assert set(ran) == set(kept), (set(ran), set(kept))
            for name in ran:
                data = ran[name].asstr()[()] if ran[name].dtype.kind == "O" else ran[name][()]
                got = kept[name].asstr()[()] if kept[name].dtype.kind == "O" else kept[name][()]
                np.testing.assert_array_equal(got, data, err_msg=name)
    assert summary["ok"] == len(runs)


def test_a_failed_run_keeps_the_rows_before_its_failure(study, scheduler):
    h5py = pytest.importorskip("h5py")
    (study.parent / "frame.toml").write_text(SCENE.replace("[solve]\n", "[solve]\nmax_steps = 5\n"))
    study.write_text(SWEEP.replace("[keep]", "[keep]\nresults = true"))
    summary = condyn.sweep(study, scheduler=scheduler, progress=False)
    assert summary["failed"] == {"step_budget": 6}
    for run in expand(read_sweep(study)):
        with pytest.raises(condyn.IntegrationError) as e:  # the same run here: the same rows
            condyn.run(scene_of(study, run))
        with h5py.File(study.parent / "study" / "runs" / f"{run.key}.h5", "r") as f:
            np.testing.assert_array_equal(f["t"][()], e.value.result.t)
            np.testing.assert_array_equal(f["displacement"][()], e.value.result.u)


def test_the_scenes_output_decides_what_a_run_computes_but_writes_no_file(study, scheduler):
    # [output] stays but for its file: the energy balance it asks for is computed, so its columns
    # have peaks, and the kept result holds it, as condyn run's file would.
    h5py = pytest.importorskip("h5py")
    quantities = '"drift", "energy"]\nfile = "frame.csv"'
    (study.parent / "frame.toml").write_text(SCENE.replace('"drift"]', quantities))
    study.write_text(SWEEP.replace('peaks = ["u2", "reaction_u1"]',
                                   'peaks = ["energy_error"]\nresults = true'))
    summary = condyn.sweep(study, scheduler=scheduler, progress=False)
    assert summary["ok"] == 6
    header, rows = read_table(summary["table"])
    for run, row in zip(expand(read_sweep(study)), rows):
        r = condyn.run(scene_of(study, run))  # the same run here: bit for bit
        error = r.energy_balance[:, r.energy_columns.index("energy_error")]
        i = int(np.argmax(np.abs(error)))
        assert float(dict(zip(header, row))["peak_energy_error"]) == abs(error[i])
        with h5py.File(study.parent / "study" / "runs" / f"{run.key}.h5", "r") as f:
            np.testing.assert_array_equal(f["energy"][()], r.energy_balance)
    assert not (study.parent / "frame.csv").exists()


def test_keep_results_must_be_a_boolean(study):
    study.write_text(SWEEP.replace("[keep]", '[keep]\nresults = "yes"'))
    with pytest.raises(condyn.SweepError, match=r"keep\.results: expected true or false"):
        condyn.sweep(study, workers=1, progress=False)


def test_peak_is_the_largest_magnitude_and_its_first_time():
    from condyn.sweep_worker import peak
    assert peak(np.array([0.0, 1.0, 2.0, 3.0]), np.array([1.0, -3.0, 3.0, 2.0])) == (3.0, 1.0)
    assert all(math.isnan(x) for x in peak(np.array([]), np.array([])))


# --- a cluster started by hand, one worker killed ------------------------------------------------

def start(command, log):
    """A process of the cluster, its output in `log`, in its own process group."""
    env = dict(os.environ, PYTHONWARNINGS="ignore")
    return subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, env=env,
                            start_new_session=True)


def test_a_worker_killed_mid_sweep_loses_no_run(study, scheduler, tmp_path):
    # 40 runs on a dask-scheduler and two dask-worker processes started as docs/sweep.md says;
    # one worker is killed (SIGKILL) once the first row is written: its runs go to the other.
    study.write_text(SWEEP.replace("values = [0.5, 1.0, 2.0]",
                                   f"values = {[0.25 * k for k in range(1, 21)]}"))
    # Runs of 10 s (the records stay at their last sample) so that the sweep outlasts the kill.
    (study.parent / "frame.toml").write_text(SCENE.replace("t_end = 1.0", "t_end = 10.0"))
    address_file = tmp_path / "scheduler.json"
    with open(tmp_path / "cluster.log", "w") as log:
        procs = [start(["dask-scheduler", "--port", "0", "--no-dashboard", "--scheduler-file",
                        str(address_file)], log)]
        try:
            deadline = time.monotonic() + 30
            while not address_file.exists() and time.monotonic() < deadline:
                time.sleep(0.1)
            address = json.loads(address_file.read_text())["address"]
            for _ in range(2):
                procs.append(start(["dask-worker", address, "--nthreads", "1", "--no-nanny",
                                    "--no-dashboard", "--local-directory", str(tmp_path)], log))
            table = study.parent / "killed" / "results.csv"
            result = {}

            def sweep():
                try:
                    result.update(condyn.sweep(study, scheduler=address, out=table.parent,
                                               progress=False))
                except Exception as e:  # shown by the assertion below
                    result["raised"] = e

            sweeping = threading.Thread(target=sweep)
            sweeping.start()
            while sweeping.is_alive() and (not table.exists() or
                                           table.read_text().count("\n") < 2):
                time.sleep(0.02)
            rows_before_kill = table.read_text().count("\n") - 1
            assert sweeping.is_alive() and rows_before_kill < 40  # the kill is mid-sweep
            procs[1].kill()
            sweeping.join(timeout=120)
            assert not sweeping.is_alive() and "raised" not in result, result
        finally:
            for p in procs:
                p.kill()
                p.wait()
    assert procs[1].returncode == -signal.SIGKILL
    assert result["runs"] == 40 and result["ok"] == 40 and result["missing"] == 0
    # The same sweep on the module's local cluster gives the same table but for wall_s.
    local = condyn.sweep(study, scheduler=scheduler, out=study.parent / "local", progress=False)
    header, rows = read_table(table)
    assert read_table(local["table"])[0] == header
    assert without_wall(header, read_table(local["table"])[1]) == without_wall(header, rows)


def test_a_task_the_scheduler_cancels_is_submitted_again_with_its_files(study, scheduler):
    # What a sweep does when the workers holding a run's files all die: the scheduler cancels
    # the task; the sweep sends the files again and submits it anew, RESUBMIT times at most.
    from condyn.sweep_run import _Tasks
    spec = read_sweep(study)
    run = expand(spec)[0]
    with distributed.Client(scheduler, set_as_default=False) as client:
        tasks = _Tasks(client, spec)
        future = tasks.submit(run)
        for attempt in range(1, _Tasks.RESUBMIT + 1):
            future.cancel()
            done, row, again = tasks.outcome(future)
            assert done is run and row is None
            assert again.key == f"condyn-run-{run.key}-{attempt}"
            future = again
        assert future.result()["status"] == "ok"
        future.cancel()
        done, row, again = tasks.outcome(future)  # no more tries: the run's row says why
        assert done is run and again is None and row["status"] == "worker_lost"


def test_a_result_lost_with_its_worker_is_submitted_again(study, scheduler):
    # A task that finished on a worker killed before the sweep gathered its result: as_completed
    # yields it finished, and its result() raises CancelledError (seen in CI with a worker killed
    # mid-sweep). The sweep submits the run again rather than stopping.
    from concurrent.futures import CancelledError
    from condyn.sweep_run import _Tasks

    class LostResult:
        def result(self):
            raise CancelledError("condyn-run-lost")

    spec = read_sweep(study)
    run = expand(spec)[0]
    with distributed.Client(scheduler, set_as_default=False) as client:
        tasks = _Tasks(client, spec)
        lost = LostResult()
        tasks.futures[lost] = (run, 0)
        done, row, again = tasks.outcome(lost)
        assert done is run and row is None and again.key == f"condyn-run-{run.key}-1"
        assert tasks.outcome(again)[1]["status"] == "ok"


# --- [records] and [scale] -----------------------------------------------------------------------

EL_CENTRO = os.path.join(os.path.dirname(__file__), "..", "..", "models", "scenes", "data",
                         "el_centro_1940_ns.csv")
RECORDS = """\
scene = "frame.toml"
[records]
folder = "suite"
column = "acceleration_g"
scale = 9.81
[scale]
pga = [0.5, 2.0]
[keep]
peaks = ["u2"]
"""


@pytest.fixture
def suite(study):
    """The study with a folder `suite` of two records in g: El Centro and a.csv with a header."""
    (study.parent / "suite").mkdir()
    shutil.copy(EL_CENTRO, study.parent / "suite" / "el_centro.csv")
    text = (study.parent / "records" / "a.csv").read_text().replace("t,a", "t,acceleration_g")
    (study.parent / "suite" / "pulse.csv").write_text(text)
    study.write_text(RECORDS)
    return study


def test_records_of_a_folder_are_scaled_to_each_target_pga(suite):
    runs = expand(read_sweep(suite))
    assert [r.values for r in runs] == [("suite/el_centro.csv", 0.5), ("suite/el_centro.csv", 2.0),
                                        ("suite/pulse.csv", 0.5), ("suite/pulse.csv", 2.0)]
    # The record's header: "Peak |a| = 0.31882 g"; the scene's table reads it in g, and the
    # scale takes that peak to the target (the unit 9.81 of [records] is replaced, its sign kept).
    table = runs[1].scene["ground_motion"]["acceleration"]
    assert table == {"type": "table", "file": "suite/el_centro.csv", "scale": 2.0 / 0.31882,
                     "column": "acceleration_g"}
    # The pulse is sin(10 t) sampled every 0.01 s: its peak is the largest sample (savetxt's
    # 19 digits read back exactly).
    t = np.arange(0.0, 1.0 + 1e-9, 0.01)
    peak = float(np.max(np.abs(np.sin(10.0 * t))))
    assert runs[2].scene["ground_motion"]["acceleration"]["scale"] == 0.5 / peak


def test_factors_multiply_each_record_and_run_on_the_cluster(suite, scheduler):
    suite.write_text(RECORDS.replace("pga = [0.5, 2.0]", "factors = [1.0, 2.0]"))
    summary = condyn.sweep(suite, scheduler=scheduler, progress=False)
    assert summary["ok"] == 4
    header, rows = read_table(summary["table"])
    assert header[:3] == ["run", "record", "scale"]
    peaks = {(r[1], r[2]): float(r[header.index("peak_u2")]) for r in rows}
    for record in ("suite/el_centro.csv", "suite/pulse.csv"):
        # A linear model: twice the record, twice the response, to the runs' accuracy (rtol
        # 1e-6 each: a relative difference within 100 rtol; observed 2.9e-6 and 0.8e-6).
        ratio = peaks[(record, "2.0")] / peaks[(record, "1.0")]
        assert abs(ratio - 2.0) < 100 * 1e-6 * 2.0


@pytest.mark.parametrize("text, key, problem", [
    (RECORDS.replace('folder = "suite"', 'folder = "empty"'), "records.folder", "holds no record"),
    (RECORDS.replace('folder = "suite"', 'folder = "nowhere"'), "records.folder", "no such folder"),
    (RECORDS.replace('folder = "suite"', 'folder = "suite"\nfiles = ["a.csv"]'), "records",
     "one of the two"),
    (RECORDS.replace('column = "acceleration_g"', 'colum = "a"'), "records.colum", "unknown key"),
    (RECORDS.replace('column = "acceleration_g"', 'column = "acc"'),
     'records (record = "suite/el_centro.csv")', "acc"),
    (RECORDS.replace("pga = [0.5, 2.0]", "pga = [0.5, -2.0]"), "scale.pga", "positive numbers"),
    (RECORDS.replace("pga = [0.5, 2.0]", "pga = [0.5]\nfactors = [1.0]"), "scale",
     "one of the three"),
    (RECORDS.replace("pga = [0.5, 2.0]", "sa = [0.5]"), "scale.period", "required with sa"),
    (RECORDS.replace("pga = [0.5, 2.0]", "sa = [0.5]\nperiod = 1.0\ndamping = 1.0"),
     "scale.damping", "in [0, 1)"),
    (RECORDS.replace("pga = [0.5, 2.0]", "pga = [0.5]\nperiod = 1.0"), "scale.period",
     "belongs to sa"),
    (RECORDS + '[[axis]]\nkey = "ground_motion.acceleration.scale"\nvalues = [1.0]\n', "records",
     "sweeps the ground motion too"),
])
def test_bad_records_and_scales_are_refused_naming_the_key(suite, text, key, problem):
    (suite.parent / "empty").mkdir()
    suite.write_text(text)
    with pytest.raises(condyn.SweepError) as e:
        expand(read_sweep(suite))
    assert str(e.value).startswith(f"{suite}: {key}"), str(e.value)
    assert problem in str(e.value), str(e.value)


def test_scale_needs_a_recorded_ground_motion(study):
    (study.parent / "frame.toml").write_text(SCENE.replace(
        '{ type = "table", file = "records/a.csv", scale = 1.0 }', "1.0"))
    study.write_text('scene = "frame.toml"\n[scale]\nfactors = [1.0]\n')
    with pytest.raises(condyn.SweepError, match=r"study.toml: scale: scales a recorded ground"):
        read_sweep(study)


# --- [ida]: curves and the fragility fit ---------------------------------------------------------

def test_the_fragility_fit_recovers_the_lognormal_the_runs_were_drawn_from():
    from scipy.stats import norm
    from condyn.sweep_ida import fragility_fit
    theta, beta, n = 2.0, 0.4, 1000
    runs = []
    for im in np.linspace(0.5, 5.0, 10):
        hits = round(n * norm.cdf(math.log(im / theta) / beta))  # exactly the expected count
        runs += [(im, 1.0)] * hits + [(im, 0.0)] * (n - hits)
    fit = fragility_fit(runs, limit=0.5)
    # Rounding each count to a whole run moves the fit by about 1/n (observed 3.3e-5 on the
    # median, 6.2e-4 on beta).
    assert abs(fit[0] / theta - 1) < 5.0 / n and abs(fit[1] / beta - 1) < 5.0 / n, fit
    assert fragility_fit([(1.0, 0.0), (2.0, 0.1)], limit=0.5) is None  # none reaches it


def test_ida_writes_curves_and_the_fit_and_refuses_what_it_cannot_draw(suite, tmp_path):
    from condyn.sweep_ida import write_ida
    columns = ["run", "record", "pga", "status", "steps", "wall_s", "peak_u2", "peak_time_u2"]
    rows = [["k", rec, str(im), "ok" if p < 9 else "convergence", "1", "0.1", str(p), "0"]
            for rec, scale in (("a", 1.0), ("b", 2.0)) for im, p in
            ((1.0, 1.0 * scale), (2.0, 2.0 * scale), (3.0, 9.0 if scale == 2.0 else 3.0))]
    fit = write_ida(str(tmp_path), columns, rows, "u2", 2.5)
    for name in ("ida.png", "ida.pdf", "fragility.png", "fragility.pdf"):
        assert (tmp_path / name).stat().st_size > 5000, name
    saved = json.loads((tmp_path / "fragility.json").read_text())
    assert saved["median"] == fit[0] and saved["runs"] == 6 and saved["intensity"] == "pga"
    # b reaches 2.5 at pga 2 (peak 4), a only at 3; b's failed run at 3 counts as reaching it.
    assert 1.0 < fit[0] < 3.0
    suite.write_text(RECORDS + '[ida]\nresponse = "u1"\n')
    with pytest.raises(condyn.SweepError, match=r"ida\.response: expected one of the kept"):
        read_sweep(suite)
    suite.write_text(RECORDS.replace("[scale]\npga = [0.5, 2.0]\n", "") +
                     '[ida]\nresponse = "u2"\n')
    with pytest.raises(condyn.SweepError,
                       match=r"study.toml: ida: needs \[records\] and \[scale\]"):
        read_sweep(suite)


def test_ida_axes_say_what_they_show_or_the_labels_given(suite, tmp_path, monkeypatch):
    # The axes read "pga" and "peak |u2|": no units and no Sa period. condyn has no units, so
    # the defaults say the quantity and "the scene's units"; [ida] may give the study's labels.
    suite.write_text(RECORDS + '[ida]\nresponse = "u2"\n')
    labels = read_sweep(suite).ida[2]
    assert labels["intensity"] == "PGA, in the scene's acceleration units"
    assert labels["response"] == "peak |u2|, in the scene's units"
    sa = RECORDS.replace("pga = [0.5, 2.0]", "sa = [0.5, 2.0]\nperiod = 0.8")
    suite.write_text(sa + '[ida]\nresponse = "u2"\n')
    assert read_sweep(suite).ida[2]["intensity"].startswith("Sa(T = 0.8, damping 0.05)")
    suite.write_text(RECORDS + '[ida]\nresponse = "u2"\nlimit = 2.5\nintensity_label = "PGA [g]"\n'
                     'response_label = "roof drift [m]"\n')
    spec = read_sweep(suite).ida
    assert spec[2] == {"intensity": "PGA [g]", "response": "roof drift [m]"}
    import matplotlib.axes
    drawn = []
    monkeypatch.setattr(matplotlib.axes.Axes, "set_xlabel", lambda ax, text: drawn.append(text))
    monkeypatch.setattr(matplotlib.axes.Axes, "set_ylabel", lambda ax, text: drawn.append(text))
    from condyn.sweep_ida import write_ida
    columns = ["run", "record", "pga", "status", "steps", "wall_s", "peak_u2", "peak_time_u2"]
    rows = [["k", rec, str(im), "ok", "1", "0.1", str(im * f), "0"]
            for rec, f in (("a", 1.0), ("b", 2.0)) for im in (1.0, 2.0)]
    write_ida(str(tmp_path), columns, rows, *spec)
    assert drawn[:3] == ["roof drift [m]", "PGA [g]", "PGA [g]"]  # IDA x, y; fragility x
    suite.write_text(RECORDS + '[ida]\nresponse = "u2"\nresponse_label = ""\n')
    with pytest.raises(condyn.SweepError, match=r"ida\.response_label: expected the axis label"):
        read_sweep(suite)


def test_the_ida_example_is_a_valid_sweep_of_records_the_script_writes():
    example = os.path.join(os.path.dirname(__file__), "..", "..", "models", "scenes", "ida")
    runs = expand(read_sweep(os.path.join(example, "frame_ida.toml")))
    assert len(runs) == 11 * 10 and len({r.key for r in runs}) == 110
    # The committed records are what make_records.py writes (its 6 decimals).
    import importlib.util
    spec = importlib.util.spec_from_file_location("make_records",
                                                  os.path.join(example, "make_records.py"))
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    t, a = script.record(3)
    saved = np.loadtxt(os.path.join(example, "records", "syn03.csv"), delimiter=",", skiprows=2)
    np.testing.assert_array_equal(saved[:, 0], np.round(t, 2))
    assert np.max(np.abs(saved[:, 1] - a)) <= 0.5e-6  # the file's rounding to 6 decimals


def test_the_ida_example_runs_and_draws_its_figures_and_fit(scheduler, tmp_path):
    # The example as a user runs it, with three of its records and three of its levels: the
    # roof reaches the 0.15 m limit under some runs only (in the full example no record at 2 m/s^2,
    # ten of eleven at 10), so the fit has both outcomes; its figures and fit are written.
    example = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "models",
                                           "scenes", "ida"))
    with open(os.path.join(example, "frame_ida.toml")) as f:
        text = f.read()
    files = [os.path.join(example, "..", "data", "el_centro_1940_ns.csv")] + [
        os.path.join(example, "records", f"syn0{k}.csv") for k in (1, 2)]
    text = text.replace('scene = "../shear_frame_el_centro.toml"',
                        f'scene = {os.path.join(example, "..", "shear_frame_el_centro.toml")!r}')
    text = re.sub(r"files = \[.*?\]", f"files = {files!r}", text, flags=re.S)
    text = re.sub(r"pga = \[.*?\]", "pga = [2.0, 6.0, 10.0]", text)
    study = tmp_path / "ida.toml"
    study.write_text(text)
    summary = condyn.sweep(study, scheduler=scheduler, progress=False)
    assert summary["runs"] == summary["ok"] == 9
    for name in ("ida.png", "ida.pdf", "fragility.png", "fragility.pdf"):
        assert (tmp_path / "ida" / name).stat().st_size > 0, name
    fit = json.loads((tmp_path / "ida" / "fragility.json").read_text())
    assert fit["runs"] == 9 and fit["limit"] == 0.15
    assert summary["fragility"] == (fit["median"], fit["beta"])
    assert 2.0 < fit["median"] < 10.0 and fit["beta"] > 0  # within the levels where it changes


# --- [monte_carlo] -------------------------------------------------------------------------------

MONTE_CARLO = """\
[monte_carlo]
samples = 4
seed = 7
[[monte_carlo.parameter]]
key = "model.mass[2][2]"
distribution = "lognormal"
median = 1.0
beta = 0.1
[[monte_carlo.parameter]]
key = "solve.rtol"
distribution = "uniform"
low = 1e-7
high = 1e-6
"""


def test_monte_carlo_draws_each_parameter_and_writes_its_values(study, scheduler):
    study.write_text(SWEEP.replace("values = [0.5, 1.0, 2.0]", "values = [1.0]") + MONTE_CARLO)
    runs = expand(read_sweep(study))
    assert [r.values for r in runs] == [(f, 1.0, k) for f in ("records/a.csv", "records/b.csv")
                                        for k in (1, 2, 3, 4)]
    # docs/sweep.md: numpy's default_rng(seed), each parameter's draws in the listed order.
    rng = np.random.default_rng(7)
    mass = 1.0 * np.exp(0.1 * rng.standard_normal(4))
    rtol = rng.uniform(1e-7, 1e-6, 4)
    for r in runs:
        assert r.scene["model"]["mass"][1][1] == mass[r.values[2] - 1]
        assert r.scene["solve"]["rtol"] == rtol[r.values[2] - 1]
    summary = condyn.sweep(study, scheduler=scheduler, progress=False)
    assert summary["ok"] == 8
    header, rows = read_table(summary["table"])
    assert header[1:6] == ["ground_motion.acceleration.file", "ground_motion.acceleration.scale",
                           "sample", "model.mass[2][2]", "solve.rtol"]
    for r, row in zip(runs, rows):
        assert row[0] == r.key and int(row[3]) == r.values[2]
        assert float(row[4]) == mass[r.values[2] - 1] and float(row[5]) == rtol[r.values[2] - 1]


@pytest.mark.parametrize("edit, key, problem", [
    (lambda s: s.replace("samples = 4", "samples = 0"), "monte_carlo.samples", ">= 1"),
    (lambda s: s.replace("seed = 7\n", ""), "monte_carlo.seed", "required"),
    (lambda s: s.replace('"lognormal"', '"weibull"'), "monte_carlo.parameter[1].distribution",
     "expected one of normal, lognormal, uniform"),
    (lambda s: s.replace("beta = 0.1", "sigma = 0.1"), "monte_carlo.parameter[1].sigma",
     "unknown key"),
    (lambda s: s.replace("beta = 0.1", "beta = -0.1"), "monte_carlo.parameter[1].beta",
     "must not be negative"),
    (lambda s: s.replace("high = 1e-6", "high = 1e-8"), "monte_carlo.parameter[2].high",
     "must not be below low"),
    (lambda s: s.replace('"solve.rtol"', '"model.mass[2][2]"'), "monte_carlo.parameter[2].key",
     "drawn already"),
    (lambda s: s.replace('"solve.rtol"', '"solve.rtoll"'),
     "monte_carlo (sample = 1)", "solve.rtoll: unknown key"),
])
def test_bad_monte_carlo_tables_are_refused_naming_the_key(study, edit, key, problem):
    study.write_text(SWEEP + edit(MONTE_CARLO))
    with pytest.raises(condyn.SweepError) as e:
        expand(read_sweep(study))
    assert str(e.value).startswith(f"{study}: {key}"), str(e.value)
    assert problem in str(e.value), str(e.value)


def test_spectral_acceleration_of_a_step_is_its_closed_form_and_scales_records():
    from condyn.sweep_records import spectral_acceleration
    # A ground acceleration a0 from t = 0 (a step): the oscillator's first peak, at
    # t = pi / omega_d, is u = (a0 / omega^2) (1 + exp(-zeta pi / sqrt(1 - zeta^2))) (Chopra,
    # Dynamics of Structures, the step force on a damped system).
    a0, period, zeta, dt = 2.0, 1.0, 0.05, 0.001
    t = np.arange(0.0, 5.0 + dt / 2, dt)
    exact = a0 * (1.0 + math.exp(-zeta * math.pi / math.sqrt(1.0 - zeta ** 2)))
    sa = spectral_acceleration(t, np.full(len(t), a0), period, zeta)
    # The maximum is taken at the samples: within (omega dt / 2)^2 / 2 = 4.9e-6 of the peak,
    # relative (observed 1.3e-6; lsim's exact first-order hold adds roundoff only).
    assert abs(sa / exact - 1.0) < 0.5 * (math.pi * dt / period) ** 2, (sa, exact)
    assert spectral_acceleration(t, np.zeros(len(t)), period, zeta) == 0.0


def test_records_scaled_to_a_spectral_acceleration(suite):
    from condyn.sweep_records import _read_record, spectral_acceleration
    suite.write_text(RECORDS.replace("pga = [0.5, 2.0]", "sa = [1.5]\nperiod = 0.5"))
    runs = expand(read_sweep(suite))
    record = _read_record(str(suite.parent / "suite" / "el_centro.csv"), "acceleration_g")
    assert runs[0].scene["ground_motion"]["acceleration"]["scale"] == \
        1.5 / spectral_acceleration(*record, 0.5, 0.05)  # damping 5 % by default


def test_schemes_and_tolerances_are_axes_over_the_solve_keys(study):
    study.write_text('schemes = ["ggl", "index1"]\ntolerances = [1e-6, 1e-8]\n' + SWEEP)
    runs = expand(read_sweep(study))
    assert len(runs) == 2 * 3 * 2 * 2
    assert [(r.scene["solve"]["scheme"], r.scene["solve"]["rtol"]) for r in runs[:4]] == [
        ("ggl", 1e-6), ("ggl", 1e-8), ("index1", 1e-6), ("index1", 1e-8)]
    study.write_text('schemes = ["ggl", "bdf"]\n' + SWEEP)
    with pytest.raises(condyn.SweepError, match=r"study.toml: schemes \(solve.scheme = \"bdf\"\): "
                       r"the scene refuses it: .*unknown scheme"):
        expand(read_sweep(study))
    study.write_text('tolerances = [1e-6]\n' + SWEEP.replace(
        "[keep]", '[[axis]]\nkey = "solve.rtol"\nvalues = [1e-8]\n[keep]'))
    with pytest.raises(condyn.SweepError, match=r"study.toml: tolerances: an \[\[axis\]\] sweeps"):
        read_sweep(study)
