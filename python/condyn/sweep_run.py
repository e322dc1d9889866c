"""Runs a sweep on Dask (docs/sweep.md): a local cluster of worker processes, or the cluster of a
scheduler the user started; each run a task carrying its scene and data files; rows written to
the results table as runs end; progress and the summary on standard error.

    summary = sweep("study.toml", workers=2)   # or scheduler="tcp://host:8786"
"""

import collections
import contextlib
import logging
import os
import signal
import sys
import time

from .sweep_file import SweepError, expand, read_sweep
from .sweep_table import ResultsTable, header
from . import sweep_worker

# The run's worker died at every try (Dask's allowed failures), or the scheduler cancelled its
# task at every one of the sweep's tries (_Tasks.RESUBMIT).
WORKER_LOST = "worker_lost"


def sweep(sweep_file, workers=None, scheduler=None, out=None, progress=sys.stderr):
    """Runs what the results table in `out` (default: the sweep file's name without extension)
    does not hold yet and returns the summary: {runs, ok, failed: {status: count}, skipped (rows
    there before), missing (runs without a row: an interrupted sweep), table, and with [ida]
    fragility: (theta, beta) or None}. Bad input raises SweepError before any run; Ctrl-C or
    SIGTERM stops the runs, keeps the rows written and returns; progress goes to `progress`
    (None: silent)."""
    if workers is not None and scheduler is not None:
        raise SweepError("--workers and --scheduler: give one (the scheduler's workers run it)")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise SweepError(f"--workers: expected a whole number >= 1 (got {workers!r})")
    spec = read_sweep(sweep_file)
    runs = expand(spec)
    table = ResultsTable(os.fspath(out) if out is not None else spec.default_out, header(spec))
    skipped = sum(1 for r in runs if r.key in table.done)
    todo = [r for r in runs if r.key not in table.done]
    try:
        if todo:
            _run_all(todo, spec, table, workers, scheduler, progress)
    except KeyboardInterrupt:
        _say(progress, "sweep: interrupted; started again on the same folder, it runs only the "
             "runs without a row")
    finally:
        table.finish([r.key for r in runs])
    summary = _summary(runs, table, skipped, spec.checks, progress)
    if spec.ida is not None:
        from .sweep_ida import write_ida
        rows = [table.done[r.key] for r in runs if r.key in table.done]
        summary["fragility"] = write_ida(table.folder, table.columns, rows, *spec.ida)
        _say(progress, f"sweep: IDA curves in {table.folder}/ida.png" + (
            f", fragility in {table.folder}/fragility.png" if spec.ida[1] is not None else ""))
    return summary


def _run_all(todo, spec, table, workers, scheduler, progress):
    """Submits every run of `todo` and writes each row as it arrives."""
    distributed = _import_distributed()
    from distributed import as_completed

    with _client(distributed, workers, scheduler, progress) as client, _stop_on_sigterm():
        _check_workers(client)
        tasks = _Tasks(client, spec)
        pending = as_completed([tasks.submit(run) for run in todo], loop=client.loop)
        meter = _Progress(progress, len(todo))
        for future in pending:
            run, row, again = tasks.outcome(future)
            if again is not None:
                pending.add(again)
                continue
            if row["status"] == sweep_worker.NO_COLUMN:
                tasks.cancel()
                raise SweepError(f"{spec.file}: keep.peaks: {row['message']}")
            if row["status"] not in sweep_worker.NOT_RUN:
                cells = [c for a, v in zip(spec.axes, run.values) for c in a.cells_of(v)]
                table.append(run.key, cells, row, spec.peaks, spec.checks)
            meter.update(row["status"])
        meter.close()


class _Tasks:
    """The runs' tasks on the cluster. Each data file is read and sent once (Client.scatter, to
    every worker: a worker that dies takes no file with it) and tasks take it from there. A task
    cancelled by the scheduler (its data lost all the same: every worker holding it died) is
    submitted again, its files sent again, up to RESUBMIT times."""

    RESUBMIT = 3

    def __init__(self, client, spec):
        self.client, self.spec = client, spec
        self.contents, self.futures = {}, {}

    def submit(self, run, attempt=0):
        files = {name: self._sent(path) for name, path in run.files.items()}
        future = self.client.submit(sweep_worker.run_one, run.scene, files, self.spec.peaks,
                                    self.spec.checks > 0, self.spec.keep_result,
                                    key=f"condyn-run-{run.key}-{attempt}", pure=False)
        self.futures[future] = (run, attempt)
        return future

    def outcome(self, future):
        """(the run of `future`, its row, None), or (the run, None, its new future) when the task
        was cancelled and is submitted again. Cancelled means by the scheduler (every worker
        holding its data died), or its result lost with its worker: a task that finished on a
        worker killed before the client gathered its result raises CancelledError from
        result() though as_completed yielded it finished (the client's gather fails, and the
        scheduler forgets the key)."""
        import distributed
        from concurrent.futures import CancelledError  # what distributed's futures raise
        run, attempt = self.futures.pop(future)
        try:
            return run, future.result(), None
        except CancelledError:
            if attempt >= self.RESUBMIT:
                return run, _lost("the scheduler cancelled the task, or lost its result, at "
                                  "each try"), None
        except distributed.KilledWorker as e:
            return run, _lost(str(e)), None
        for path in run.files.values():
            self.contents.pop(path, None)
        return run, None, self.submit(run, attempt + 1)

    def cancel(self):
        for f in self.futures:
            f.cancel()

    def _sent(self, path):
        if path not in self.contents:
            with open(path, "rb") as f:
                self.contents[path] = self.client.scatter(f.read(), hash=False, broadcast=True)
        return self.contents[path]


def _lost(message):
    """The row of a run whose task could not end: its worker died at each try, or the scheduler
    cancelled it again and again."""
    return {"status": WORKER_LOST, "steps": None, "wall_s": None, "peaks": {}, "message": message}


def _import_distributed():
    try:
        import distributed
    except ImportError as e:
        raise RuntimeError("condyn sweep needs Dask: apt-get install python3-distributed "
                           f"python3-dask ({e})") from None
    # The cluster's own chatter (workers starting and closing) is not the sweep's output.
    for name in ("distributed", "tornado", "asyncio"):
        logging.getLogger(name).setLevel(logging.CRITICAL)
    return distributed


@contextlib.contextmanager
def _client(distributed, workers, scheduler, progress):
    """A client of the scheduler at `scheduler`, or of a local cluster of `workers` processes
    (default: one per core), one thread each (a run holds its core); closed on leaving."""
    if scheduler is None:
        count = workers or os.cpu_count() or 1
        # Several workers share the cores already: each run keeps to its thread (condyn's second
        # lane, CONDYN_NUM_THREADS, would only compete with the next worker's run).
        env = {"CONDYN_NUM_THREADS": "1"} if count > 1 else {}
        # The workers start with Ctrl-C ignored: it stops the sweep, which closes them (they
        # would otherwise each print a KeyboardInterrupt's traceback as they die).
        with _sigint_ignored():
            cluster = distributed.LocalCluster(n_workers=count, threads_per_worker=1,
                                               processes=True, dashboard_address=None,
                                               silence_logs=logging.CRITICAL, env=env)
        with cluster, distributed.Client(cluster, set_as_default=False) as client:
            yield client
        return
    try:
        client = distributed.Client(scheduler, timeout=20, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as e:
        raise RuntimeError(f"--scheduler {scheduler}: cannot reach the scheduler ({e})") from None
    with client:
        if not client.scheduler_info()["workers"]:
            _say(progress, f"sweep: the scheduler at {scheduler} has no workers yet; waiting "
                 "for one (dask-worker " + scheduler + ")")
            client.wait_for_workers(1)
        yield client


def _check_workers(client):
    """Every worker must import condyn (a remote worker started without its PYTHONPATH would
    fail every task): RuntimeError naming the workers that cannot."""
    def probe():
        import condyn
        return condyn.__name__

    try:
        client.run(probe)
    except ImportError as e:
        raise RuntimeError(f"a worker cannot import condyn ({e}): start dask-worker with "
                           "PYTHONPATH set to the folder holding condyn (docs/sweep.md)") from None


@contextlib.contextmanager
def _sigint_ignored():
    """SIGINT ignored while processes are started (they inherit it), in the main thread only."""
    try:
        previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    except ValueError:  # not the main thread: leave signals alone
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


class _stop_on_sigterm:
    """SIGTERM stops the sweep as Ctrl-C does: the rows written stay, the table is finished."""

    def __enter__(self):
        def stop(signum, frame):
            raise KeyboardInterrupt

        try:
            self.previous = signal.signal(signal.SIGTERM, stop)
        except ValueError:  # not the main thread: leave signals alone
            self.previous = None
        return self

    def __exit__(self, *exc):
        if self.previous is not None:
            signal.signal(signal.SIGTERM, self.previous)


class _Progress:
    """Runs done and failed, runs per second and the time left, on one line rewritten on a
    terminal, else a line every 10 % of the runs or 10 s."""

    def __init__(self, stream, total):
        self.stream, self.total = stream, total
        self.done = self.failed = 0
        self.start = self.last = time.monotonic()
        self.tty = stream is not None and hasattr(stream, "isatty") and stream.isatty()

    def update(self, status):
        self.done += 1
        self.failed += status != "ok"
        now = time.monotonic()
        step = max(1, self.total // 10)
        if self.tty or self.done % step == 0 or self.done == self.total or now - self.last > 10:
            self.last = now
            self._print(now)

    def close(self):
        if self.tty:
            self.stream.write("\n")

    def _print(self, now):
        if self.stream is None:
            return
        rate = self.done / max(now - self.start, 1e-9)
        left = (self.total - self.done) / rate if rate > 0 else float("inf")
        line = (f"sweep: {self.done}/{self.total} runs, {self.failed} failed, "
                f"{rate:.3g} runs/s, {left:.0f} s left")
        self.stream.write(("\r" + line + "\033[K") if self.tty else line + "\n")
        self.stream.flush()


def _summary(runs, table, skipped, checks, progress):
    rows = [dict(zip(table.columns, table.done[r.key])) for r in runs if r.key in table.done]
    statuses = collections.Counter(row["status"] for row in rows)
    failed = {s: n for s, n in sorted(statuses.items()) if s != "ok"}
    summary = {"runs": len(runs), "ok": statuses.get("ok", 0), "failed": failed,
               "skipped": skipped, "missing": len(runs) - sum(statuses.values()),
               "table": table.csv_path}
    kinds = ", ".join(f"{s} {n}" for s, n in failed.items())
    verdicts = ""
    if checks:
        summary["checks"] = _check_counts(rows, checks)
        c = summary["checks"]
        each = ", ".join(f"{k} {n}" for k, n in c["failed_by_check"].items())
        verdicts = (f"; checks: {c['passed']} runs passed, {c['failed']} failed"
                    f"{f' ({each})' if each else ''}")
    _say(progress, f"sweep: {summary['runs']} runs: {summary['ok']} ok, "
         f"{sum(failed.values())} failed{f' ({kinds})' if kinds else ''}, "
         f"{summary['missing']} not run{verdicts}; {skipped} done before; "
         f"results in {table.csv_path}")
    return summary


def _check_counts(rows, checks):
    """Of the runs that succeeded: how many passed every check (and held their constraints),
    how many did not, and per check how many runs failed it (checks that failed nowhere left
    out)."""
    done = [row for row in rows if row["checks_passed"] != ""]
    by_check = {f"check{k}": sum(row[f"check{k}_passed"] == "false" for row in done)
                for k in range(1, checks + 1)}
    return {"passed": sum(row["checks_passed"] == "true" for row in done),
            "failed": sum(row["checks_passed"] == "false" for row in done),
            "failed_by_check": {k: n for k, n in by_check.items() if n}}


def _say(stream, line):
    if stream is not None:
        stream.write(line + "\n")
        stream.flush()
