"""Command line: run a deck into a JSON record, describe or render a dump.

  python3 -m slender run DECK [-v key=value ...] [-t N] [--json OUT.json] [--timeout S] [--keep DIR]
  python3 -m slender info FILE.h5
  python3 -m slender render FILE.h5 OUT.png [--frame -1] [--radius R] [--field NAME]

`run` writes the record (status, returncode, wall_s, variables, result, results, error)
to OUT.json (else to stdout) and exits 1 unless the status is ok: one Snakemake rule per
deck run. The binary comes from $SLENDER_BIN, else build/slender, else PATH.
"""

import argparse
import json
import os
import signal
import sys

from . import run


def _terminate_on_sigterm():
    """A cancelled job (Snakemake, Slurm) gets SIGTERM: turn it into an exception, so
    run_deck stops the deck (which writes its last frame and checkpoint) before we exit."""
    def handler(signum, _frame):
        raise SystemExit(128 + signum)
    signal.signal(signal.SIGTERM, handler)


def write_json(record, path):
    """Write the record whole or not at all (a rule's output must never be half a file)."""
    text = json.dumps(record, indent=1) + "\n"
    if path is None:
        sys.stdout.write(text)
        return
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    tmp = path + ".tmp"
    with open(tmp, "w") as fh:
        fh.write(text)
    os.replace(tmp, path)


def cmd_run(a):
    _terminate_on_sigterm()
    res = run.run_deck(a.deck, a.var, threads=a.threads, cwd=a.keep, timeout=a.timeout)
    write_json(res.to_dict(), a.json)
    if not res.ok:
        print(f"slender run: {a.deck}: {res.status}: {res.error}", file=sys.stderr)
    return 0 if res.ok else 1


def cmd_info(a):
    from . import io
    for line in io.describe(a.file):
        print(line)
    return 0


def cmd_render(a):
    from . import plot
    step = plot.render(a.file, a.out, a.frame, field=a.field, radius=a.radius)
    print(f"wrote {a.out} (step {step})")
    return 0


def main(argv=None):
    p = argparse.ArgumentParser(prog="python3 -m slender", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="run a deck, write its result as JSON")
    r.add_argument("deck")
    r.add_argument("-v", dest="var", action="append", default=[], metavar="KEY=VALUE",
                   help="a deck variable (repeatable)")
    r.add_argument("-t", dest="threads", type=int, default=1, help="threads (default 1)")
    r.add_argument("--json", help="write the record here (default: stdout)")
    r.add_argument("--timeout", type=float, help="stop the run after S seconds (status timeout)")
    r.add_argument("--keep", metavar="DIR", help="run in DIR and keep its outputs there "
                   "(default: a temporary folder, removed)")
    r.set_defaults(func=cmd_run)
    i = sub.add_parser("info", help="what a trajectory, shell surface or checkpoint holds")
    i.add_argument("file")
    i.set_defaults(func=cmd_info)
    d = sub.add_parser("render", help="a frame of a trajectory or shell surface as a PNG")
    d.add_argument("file")
    d.add_argument("out")
    d.add_argument("--frame", type=int, default=-1)
    d.add_argument("--radius", type=float, help="2D: cavity circle; 3D: half side of the box")
    d.add_argument("--field", help="colour by a per-node field (trajectory) or per-face field (surface)")
    d.set_defaults(func=cmd_render)
    a = p.parse_args(argv)
    try:
        return a.func(a)
    except (OSError, ValueError, KeyError, IndexError) as e:
        print(f"python3 -m slender {a.command}: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
