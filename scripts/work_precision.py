#!/usr/bin/python3
"""Work-precision sweep: error against run time for the validation decks.

Runs the `slender` binary on the validation decks over a ladder of node
counts and integrators, parses the `RESULT key=value ...` lines the decks
print, and writes

    OUT/work_precision.csv   one row per RESULT line (failed runs included)
    OUT/work_precision.md    one Markdown table per case variant
    OUT/work_precision.png   log-log rel_error vs wall_s, one panel per variant

Decks (under --decks, default examples/validation):
    cantilever2d.lua  -v nodes=N -v integrator=I [-v dt=X] -v alpha=A
    buckling2d.lua    -v nodes=N -v integrator=I -v bc=pinned|clamped

RESULT format assumed: a line whose first whitespace-separated token is
`RESULT`, followed by `key=value` tokens without embedded spaces (split at the
first '='); values are kept verbatim as strings and converted to numbers only
for formatting and plotting.  Every RESULT line of a run becomes one row.

Each run gets its own temporary working directory (deleted afterwards) so
deck output files do not litter the tree.  A failing run (non-zero exit,
timeout, or no RESULT line) is recorded with status and the last stderr line,
and the sweep continues.  Exit status: 0 if every run succeeded, 1 if some
failed (outputs are written either way), 2 on usage/setup errors.

Examples:
    /usr/bin/python3 scripts/work_precision.py --fast
    /usr/bin/python3 scripts/work_precision.py --dt-ladder --cases cantilever
    /usr/bin/python3 scripts/work_precision.py --replot     # redo md/png from csv
"""

import argparse
import csv
import datetime
import math
import os
import shlex
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "python"))
import slender.run as slender_run  # noqa: E402

DEFAULT_NODES = [11, 21, 41, 81]
DEFAULT_INTEGRATORS = ["verlet", "gear5", "gear6", "fire"]
FAST_NODES = [11, 21]
FAST_INTEGRATORS = ["verlet", "gear5"]
DEFAULT_ALPHAS = [0.1, 3.0]
DEFAULT_BCS = ["pinned", "clamped"]
DECK_FILES = {"cantilever": "cantilever2d.lua", "buckling": "buckling2d.lua",
              "michell": "michell.lua", "plate": "plate_load.lua"}
# Michell's ring needs more nodes than a beam to be resolved (12 is too coarse)
MICHELL_NODES = [12, 24, 48]
# Koiter shell plates (cells per side), both supports (FIRE to static equilibrium)
PLATE_CELLS = [8, 16, 32]
PLATE_SUPPORTS = ["simply_supported", "clamped"]

# CSV columns that always come first (in this order); the remaining RESULT
# keys follow in first-seen order, then the bookkeeping columns.
LEAD_COLUMNS = ["case", "alpha", "bc", "nodes", "integrator", "dt", "dt_mode",
                "rel_error", "wall_s", "status", "error"]
TAIL_COLUMNS = ["returncode", "run_s", "cmd"]


# ----------------------------------------------------------------------------
# Running and parsing
# ----------------------------------------------------------------------------

def to_float(value):
    """float(value) or None if it is not a number."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        return None
    return x


def run_deck(binary, deck, overrides, timeout, base_row):
    """Run one deck with `-v name=value` overrides; return a list of rows.

    base_row holds the requested parameters; RESULT keys override them.
    """
    res = slender_run.run_deck(deck, overrides, timeout=timeout, binary=binary)
    row0 = dict(base_row)
    row0["cmd"] = " ".join(shlex.quote(c) for c in res.command)
    row0["run_s"] = "%.3f" % res.wall_s
    if res.status != "timeout" and res.returncode is not None:
        row0["returncode"] = str(res.returncode)
    rows = []
    for rec in res.results_text or [{}]:
        row = dict(row0)
        for key, value in rec.items():
            if key in base_row and base_row[key] not in ("", None) \
                    and key not in ("dt",) and not same_value(base_row[key], value):
                print("  warning: RESULT %s=%s differs from requested %s"
                      % (key, value, base_row[key]), file=sys.stderr)
            row[key] = value
        row["status"], row["error"] = res.status, res.error
        rows.append(row)
    return rows


def same_value(a, b):
    """Compare two values as numbers if both parse, else as strings."""
    fa, fb = to_float(a), to_float(b)
    if fa is not None and fb is not None:
        return math.isclose(fa, fb, rel_tol=1e-9, abs_tol=0.0)
    return str(a) == str(b)


# ----------------------------------------------------------------------------
# Case variants (one table / one panel each)
# ----------------------------------------------------------------------------

def variant_key(row):
    """(sort key, title) identifying the case variant of a row."""
    case = row.get("case", "")
    if case.startswith("cantilever"):
        a = to_float(row.get("alpha"))
        label = "%g" % a if a is not None else str(row.get("alpha"))
        kind = "small load" if a is not None and a < 1 else "large load"
        model = row.get("model") or "bend2d"
        return ((0, a if a is not None else math.inf, label, model),
                "cantilever, alpha = %s (%s), %s" % (label, kind, model))
    if case.startswith("michell"):
        return ((2, 0, "michell"), "michell ring, cosserat rod (gear6)")
    if case.startswith("plate"):
        bc = row.get("bc", "")
        return ((2, 1 + (PLATE_SUPPORTS.index(bc) if bc in PLATE_SUPPORTS else 2), bc),
                "plate under uniform load, %s, koiter shell (fire)" % bc)
    if case.startswith("buckling"):
        bc = row.get("bc", "")
        order = DEFAULT_BCS.index(bc) if bc in DEFAULT_BCS else len(DEFAULT_BCS)
        model = row.get("model") or "bend2d"
        return ((1, order, bc, model), "buckling, %s, %s" % (bc, model))
    return ((3, 0, case), case or "unknown case")


def group_variants(rows):
    """Ordered list of (title, rows) per case variant."""
    groups = {}
    for row in rows:
        key, title = variant_key(row)
        groups.setdefault(key, (title, []))[1].append(row)
    return [groups[k] for k in sorted(groups, key=lambda k: (k[0], k[1], str(k[2])))]


def integrator_order(name):
    return (DEFAULT_INTEGRATORS.index(name) if name in DEFAULT_INTEGRATORS
            else len(DEFAULT_INTEGRATORS), name)


def row_sort_key(row):
    nodes = to_float(row.get("nodes"))
    dt = to_float(row.get("dt"))
    return (integrator_order(row.get("integrator", "")),
            nodes if nodes is not None else math.inf,
            -(dt if dt is not None else math.inf))


def x_time(row):
    """Run time for plots: the deck's wall_s, else the script's measurement."""
    t = to_float(row.get("wall_s"))
    return t if t is not None else to_float(row.get("run_s"))


# ----------------------------------------------------------------------------
# Outputs
# ----------------------------------------------------------------------------

def csv_columns(rows):
    keys = []
    for row in rows:
        for k in row:
            if k not in keys:
                keys.append(k)
    middle = [k for k in keys if k not in LEAD_COLUMNS and k not in TAIL_COLUMNS]
    return ([k for k in LEAD_COLUMNS if k in keys] + middle
            + [k for k in TAIL_COLUMNS if k in keys])


def write_csv(path, rows):
    cols = csv_columns(rows)
    tmp = path.with_suffix(".csv.tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, restval="")
        w.writeheader()
        for row in rows:
            w.writerow(row)
    os.replace(tmp, path)   # atomic: a partial sweep never leaves a torn file


def read_csv(path):
    with open(path, newline="") as f:
        return [dict(r) for r in csv.DictReader(f)]


def fmt(value, spec):
    x = to_float(value)
    if x is None:
        return str(value) if value not in (None, "") else "—"
    return spec % x


def md_escape(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def write_markdown(path, rows, header_lines):
    out = ["# Work-precision sweep", ""]
    out += header_lines
    out += ["", "rel_error: relative error against the reference computed inside "
            "the deck; wall_s: run time reported by the deck (seconds).", ""]
    for title, grp in group_variants(rows):
        is_buckling = title.startswith("buckling")
        extra = ["pc", "ref", "runs"] if is_buckling else ["steps"]
        extra = [k for k in extra if any(r.get(k, "") != "" for r in grp)]
        has_mode = any(r.get("dt_mode", "") not in ("", "auto") for r in grp)
        has_dt = any(to_float(r.get("dt")) is not None for r in grp)
        cols = ["integrator", "nodes"] + (["dt"] if has_dt else []) \
            + (["dt_mode"] if has_mode else []) + ["rel_error", "wall_s"] + extra \
            + ["status"]
        out += ["## " + title, "",
                "| " + " | ".join(cols) + " |",
                "|" + "|".join("---" for _ in cols) + "|"]
        for r in sorted(grp, key=row_sort_key):
            cells = []
            for c in cols:
                if c == "rel_error":
                    cells.append(fmt(r.get(c), "%.2e"))
                elif c == "wall_s":
                    cells.append(fmt(r.get(c), "%.3g"))
                elif c in ("dt", "pc", "ref"):
                    cells.append(fmt(r.get(c), "%.4g"))
                elif c == "status":
                    st = r.get("status", "")
                    cells.append("ok" if st == "ok" else
                                 md_escape("%s: %s" % (st, r.get("error", ""))))
                else:
                    cells.append(md_escape(r.get(c, "") or "—"))
            out.append("| " + " | ".join(cells) + " |")
        out.append("")
    path.write_text("\n".join(out))


def write_plot(path, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    groups = group_variants(rows)
    n = max(1, len(groups))
    ncols = 2 if n > 1 else 1
    nrows = (n + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(6.0 * ncols, 4.6 * nrows),
                             squeeze=False)
    integrators = sorted({r.get("integrator", "") for r in rows}, key=integrator_order)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    markers = "osD^vP*X"
    style = {name: (colors[i % len(colors)], markers[i % len(markers)])
             for i, name in enumerate(integrators)}

    for ax, (title, grp) in zip(axes.flat, groups):
        plotted = False
        for integ in integrators:
            pts = []
            for r in grp:
                if r.get("integrator") != integ or r.get("status") != "ok":
                    continue
                e, t = to_float(r.get("rel_error")), x_time(r)
                if e is None or t is None or e == 0 or t <= 0:
                    continue   # cannot be shown on log axes
                pts.append((r, t, abs(e)))
            if not pts:
                continue
            color, marker = style[integ]
            # node ladder at the automatic time step
            main = sorted([p for p in pts if p[0].get("dt_mode", "auto") in ("", "auto")],
                          key=lambda p: to_float(p[0].get("nodes")) or 0)
            if main:
                ax.plot([p[1] for p in main], [p[2] for p in main], "-",
                        color=color, marker=marker, label=integ)
                for r, t, e in main:
                    ax.annotate(r.get("nodes", ""), (t, e), textcoords="offset points",
                                xytext=(4, 4), fontsize=7, color=color)
            # dt ladder (finest nodes): dashed, open markers, starting at auto dt
            refined = [p for p in pts if p[0].get("dt_mode", "auto") not in ("", "auto")]
            if refined:
                nodes = refined[0][0].get("nodes")
                start = [p for p in main if p[0].get("nodes") == nodes]
                chain = sorted(start + refined,
                               key=lambda p: -(to_float(p[0].get("dt")) or 0))
                ax.plot([p[1] for p in chain], [p[2] for p in chain], "--",
                        color=color, marker=marker, markerfacecolor="none",
                        label="%s, dt/2^k (nodes=%s)" % (integ, nodes))
            plotted = True
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("relative error")
        if plotted:
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
        else:
            ax.text(0.5, 0.5, "no successful runs", ha="center", va="center",
                    transform=ax.transAxes)
    for ax in list(axes.flat)[len(groups):]:
        ax.set_visible(False)
    fig.suptitle("slender work-precision (labels: nodes)", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def write_outputs(out_dir, rows, header_lines):
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = {k: out_dir / ("work_precision." + k) for k in ("csv", "md", "png")}
    write_csv(paths["csv"], rows)
    write_markdown(paths["md"], rows, header_lines)
    write_plot(paths["png"], rows)
    return paths


# ----------------------------------------------------------------------------
# Sweep
# ----------------------------------------------------------------------------

def git_describe():
    try:
        return subprocess.run(["git", "-C", str(REPO), "describe", "--always", "--dirty"],
                              capture_output=True, text=True, timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""


def build_plan(args, decks):
    """List of (deck, overrides, base_row) for the main ladder."""
    plan = []
    if "cantilever" in decks:
        for model in args.models:
            for alpha in args.alphas:
                for integ in args.integrators:
                    for nodes in args.nodes:
                        base = {"case": "cantilever2d", "model": model, "alpha": repr(alpha),
                                "nodes": str(nodes), "integrator": integ, "dt": "auto",
                                "dt_mode": "auto"}
                        ov = [("nodes", nodes), ("integrator", integ), ("alpha", repr(alpha)),
                              ("model", model)]
                        plan.append((decks["cantilever"], ov, base))
    if "buckling" in decks:
        for model in args.models:
            for bc in args.bcs:
                for integ in args.integrators:
                    for nodes in args.nodes:
                        base = {"case": "buckling2d", "model": model, "bc": bc,
                                "nodes": str(nodes), "integrator": integ}
                        ov = [("nodes", nodes), ("integrator", integ), ("bc", bc),
                              ("model", model)]
                        plan.append((decks["buckling"], ov, base))
    if "michell" in decks:
        # the deck integrates with gear q = 6 itself; the ladder is over nodes
        for nodes in args.michell_nodes:
            base = {"case": "michell", "nodes": str(nodes), "integrator": "gear6"}
            plan.append((decks["michell"], [("nodes", nodes), ("iterations", 12)], base))
    if "plate" in decks:
        # the ladder is over cells per side; the rows report nodes = (cells + 1)^2
        for support in PLATE_SUPPORTS:
            for cells in args.plate_cells:
                base = {"case": "plate_load", "bc": support, "nodes": str((cells + 1) ** 2),
                        "integrator": "fire"}
                plan.append((decks["plate"], [("n", cells), ("support", support)], base))
    return plan


def describe(base):
    parts = [base.get("case", "")]
    for k in ("model", "alpha", "bc", "nodes", "integrator", "dt_mode"):
        if base.get(k):
            parts.append("%s=%s" % (k, base[k]))
    return " ".join(parts)


def main(argv=None):
    p = argparse.ArgumentParser(
        description="Error-against-run-time sweep of slender's validation decks.",
        epilog="Exit status: 0 all runs ok, 1 some runs failed (outputs still "
               "written), 2 setup error.")
    p.add_argument("--slender", default=str(REPO / "build" / "slender"),
                   help="path to the slender executable (default %(default)s)")
    p.add_argument("--decks", default=str(REPO / "examples" / "validation"),
                   help="directory holding cantilever2d.lua and buckling2d.lua "
                        "(default %(default)s)")
    p.add_argument("--out", default=str(REPO / "docs" / "validation"),
                   help="output directory (default %(default)s)")
    p.add_argument("--cases", nargs="+", choices=sorted(DECK_FILES),
                   default=sorted(DECK_FILES), help="which decks to run (default: all)")
    p.add_argument("--nodes", type=int, nargs="+", default=None,
                   help="node counts (default %s; --fast: %s)" % (DEFAULT_NODES, FAST_NODES))
    p.add_argument("--integrators", nargs="+", default=None,
                   help="integrators (default %s; --fast: %s)"
                        % (DEFAULT_INTEGRATORS, FAST_INTEGRATORS))
    p.add_argument("--alphas", type=float, nargs="+", default=DEFAULT_ALPHAS,
                   help="cantilever load parameters alpha = P L^2/EI (default %(default)s)")
    p.add_argument("--models", nargs="+", default=["bend2d", "rod3d"],
                   help="beam models: bend2d (2D bending springs), rod3d (3D discrete elastic "
                        "rod, bond rod/straight), cosserat (quaternion rod; not with fire) "
                        "(default %(default)s)")
    p.add_argument("--plate-cells", type=int, nargs="+", default=PLATE_CELLS,
                   help="cells per side of the shell plate ladder")
    p.add_argument("--michell-nodes", type=int, nargs="+", default=MICHELL_NODES,
                   help="node counts of the Michell ring (default %(default)s)")
    p.add_argument("--bcs", nargs="+", default=DEFAULT_BCS,
                   help="buckling boundary conditions (default %(default)s)")
    p.add_argument("--dt-ladder", action="store_true",
                   help="cantilever, finest nodes: also run dt = auto/f for each "
                        "--dt-factors f, auto dt read from the auto run's RESULT")
    p.add_argument("--dt-factors", type=float, nargs="+", default=[2.0, 4.0],
                   help="divisors of the auto dt used by --dt-ladder (default %(default)s)")
    p.add_argument("--fast", action="store_true",
                   help="quick check: nodes %s, integrators %s (explicit "
                        "--nodes/--integrators still win)" % (FAST_NODES, FAST_INTEGRATORS))
    p.add_argument("--timeout", type=float, default=600.0,
                   help="per-run timeout in seconds (default %(default)s)")
    p.add_argument("-v", "--var", action="append", default=[], metavar="NAME=VALUE",
                   help="extra -v override passed to every run (repeatable)")
    p.add_argument("--dry-run", action="store_true",
                   help="print the main-ladder commands and exit")
    p.add_argument("--replot", action="store_true",
                   help="do not run anything; rebuild md/png from OUT/work_precision.csv")
    args = p.parse_args(argv)

    if args.nodes is None:
        args.nodes = FAST_NODES if args.fast else DEFAULT_NODES
    if args.integrators is None:
        args.integrators = FAST_INTEGRATORS if args.fast else DEFAULT_INTEGRATORS
    extra = []
    for item in args.var:
        name, sep, value = item.partition("=")
        if not sep or not name:
            p.error("-v expects NAME=VALUE, got %r" % item)
        extra.append((name, value))
    out_dir = Path(args.out)

    if args.replot:
        csv_path = out_dir / "work_precision.csv"
        if not csv_path.is_file():
            print("error: %s not found" % csv_path, file=sys.stderr)
            return 2
        rows = read_csv(csv_path)
        paths = write_outputs(out_dir, rows, ["Re-plotted from `%s`." % csv_path.name])
        for k in ("csv", "md", "png"):
            print("wrote %s" % paths[k])
        return 0

    slender = Path(args.slender).resolve()
    deck_dir = Path(args.decks).resolve()
    decks = {}
    for case in args.cases:
        deck = deck_dir / DECK_FILES[case]
        if deck.is_file():
            decks[case] = deck
        else:
            print("warning: deck %s not found, skipping %s" % (deck, case), file=sys.stderr)
    if not decks:
        print("error: no decks to run", file=sys.stderr)
        return 2

    plan = build_plan(args, decks)
    if args.dry_run:
        for deck, ov, base in plan:
            argv_ = [str(slender), str(deck), "-q"]
            for n, v in ov + extra:
                argv_ += ["-v", "%s=%s" % (n, v)]
            print(" ".join(shlex.quote(c) for c in argv_))
        if args.dt_ladder:
            print("# plus, with --dt-ladder: cantilever nodes=%d reruns at dt = auto/%s"
                  % (max(args.nodes), ", auto/".join("%g" % f for f in args.dt_factors)))
        return 0

    if not (slender.is_file() and os.access(slender, os.X_OK)):
        print("error: slender executable not found at %s (use --slender)" % slender,
              file=sys.stderr)
        return 2

    started = datetime.datetime.now()
    header = ["- date: %s" % started.strftime("%Y-%m-%d %H:%M"),
              "- slender: `%s`" % slender,
              "- git: `%s`" % (git_describe() or "unknown"),
              "- command: `%s`" % " ".join(shlex.quote(a) for a in
                                          [Path(sys.argv[0]).name] + sys.argv[1:])]
    out_dir.mkdir(parents=True, exist_ok=True)
    csv_path = out_dir / "work_precision.csv"
    rows = []

    def do_run(deck, ov, base, label):
        new = run_deck(slender, deck, ov + extra, args.timeout, base)
        rows.extend(new)
        for r in new:
            if r["status"] == "ok":
                print("%s ok  rel_error=%s wall_s=%s dt=%s (%s s)"
                      % (label, fmt(r.get("rel_error"), "%.2e"),
                         fmt(r.get("wall_s"), "%.3g"), fmt(r.get("dt"), "%.4g"),
                         r.get("run_s")), flush=True)
            else:
                print("%s %s: %s" % (label, r["status"].upper(), r.get("error")), flush=True)
        write_csv(csv_path, rows)   # keep partial results if interrupted
        return new

    total = len(plan)
    for i, (deck, ov, base) in enumerate(plan, 1):
        do_run(deck, ov, base, "[%d/%d] %s" % (i, total, describe(base)))

    # dt ladder: finest nodes, auto dt read back from the auto run's RESULT
    if args.dt_ladder and "cantilever" in decks:
        finest = str(max(args.nodes))
        for alpha in args.alphas:
            for integ in args.integrators:
                auto = [r for r in rows if r.get("case") == "cantilever2d"
                        and (r.get("model") or "bend2d") == "bend2d"
                        and same_value(r.get("alpha"), alpha) and r.get("integrator") == integ
                        and r.get("nodes") == finest and r.get("dt_mode") == "auto"
                        and r.get("status") == "ok"]
                dt0 = to_float(auto[0].get("dt")) if auto else None
                if dt0 is None or dt0 <= 0:
                    print("dt-ladder: no usable auto dt for alpha=%g %s nodes=%s, skipped"
                          % (alpha, integ, finest), file=sys.stderr)
                    continue
                for f in args.dt_factors:
                    dt = dt0 / f
                    base = {"case": "cantilever2d", "model": "bend2d", "alpha": repr(alpha),
                            "nodes": finest, "integrator": integ, "dt": repr(dt),
                            "dt_mode": "auto/%g" % f}
                    ov = [("nodes", finest), ("integrator", integ), ("alpha", repr(alpha)),
                          ("dt", repr(dt))]
                    do_run(decks["cantilever"], ov, base, "[dt] %s" % describe(base))

    elapsed = (datetime.datetime.now() - started).total_seconds()
    header.append("- sweep time: %.1f s, %d rows" % (elapsed, len(rows)))
    paths = write_outputs(out_dir, rows, header)
    failed = [r for r in rows if r.get("status") != "ok"]
    print("\n%d runs, %d failed" % (len(rows), len(failed)))
    for k in ("csv", "md", "png"):
        print("wrote %s" % paths[k])
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
