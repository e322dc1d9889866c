"""`condyn sweep SWEEP.toml [--workers N] [--scheduler ADDRESS] [--out DIR]` (docs/sweep.md): the
command line of condyn.sweep, which the condyn executable runs as
`/usr/bin/python3 -m condyn.sweep_cli ...`. Exit 0 when every run succeeded, 1 when some failed
or did not run (or the cluster could not be used), 2 for bad input (the file and key named).
"""

import argparse
import sys

from .sweep_file import SweepError


def _workers(text):
    try:
        n = int(text)
    except ValueError:
        n = 0
    if n < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 1 (got '{text}')")
    return n


def _parser():
    p = argparse.ArgumentParser(
        prog="condyn sweep", description="runs the product of a sweep file's axes on Dask and "
        "writes DIR/results.csv (docs/sweep.md)")
    p.add_argument("sweep", help="the sweep file (TOML)")
    p.add_argument("--workers", type=_workers, help="worker processes of the local cluster "
                   "(default: one per core)")
    p.add_argument("--scheduler", help="the address of a running Dask scheduler "
                   "(tcp://host:8786) whose workers run the sweep")
    p.add_argument("--out", help="the results folder (default: the sweep file's name without "
                   "extension, beside it)")
    return p


def main(argv=None):
    args = _parser().parse_args(argv)  # a usage error exits 2, as condyn's commands do
    if args.scheduler is not None and not args.scheduler.startswith(("tcp://", "tls://")):
        print(f"error: --scheduler: expected an address tcp://host:port (got "
              f"'{args.scheduler}')", file=sys.stderr)
        return 2
    from .sweep_run import sweep
    try:
        summary = sweep(args.sweep, workers=args.workers, scheduler=args.scheduler, out=args.out)
    except SweepError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except RuntimeError as e:  # no Dask, an unreachable scheduler, workers without condyn
        print(f"error: {e}", file=sys.stderr)
        return 1
    return 0 if summary["ok"] == summary["runs"] else 1


if __name__ == "__main__":
    sys.exit(main())
