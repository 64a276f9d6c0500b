"""The studies' tables and plots from their per-point JSON records, drawn and classified
by the existing scripts (scripts/phase_diagram.py, scripts/pack3d_sweep.py,
scripts/run-examples), whose functions are imported, not copied."""
import importlib.machinery
import importlib.util
import os
import re
import sys

import numpy as np

from sweep import write_table

SCRIPTS = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                       "scripts")
sys.path.insert(0, SCRIPTS)

import crumple_study  # noqa: E402
import first_buckle  # noqa: E402
import pack3d_sweep  # noqa: E402
import phase_diagram  # noqa: E402


def _import_script(name, path):
    """A script without the .py suffix, as a module."""
    loader = importlib.machinery.SourceFileLoader(name, path)
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader(name, loader))
    loader.exec_module(module)
    return module


run_examples = _import_script("run_examples", os.path.join(SCRIPTS, "run-examples"))

EXAMPLE_FIELDS = ["deck", "status", "wall_s", "headline"]


def diagram_row(record):
    """A row of scripts/phase_diagram.py's table: a run the guard stopped is classified
    from its last good state (status unstable)."""
    var, res = record["variables"], record["result"]
    row = {k: var[k] for k in ("f", "s", "yield", "mu", "seed")}
    row["dt"] = var.get("dt", "auto")
    row.update((k, res[k]) for k in ("phi", "jammed", "loops", "winding", "ab_ratio", "contacts",
                                     "steps", "wall_s"))
    row["class"] = phase_diagram.classify(row)
    row["status"] = "ok" if record["status"] == "ok" else "unstable"
    row["error"] = record["error"]
    if "retried_with" in record:  # as the script writes it
        row["error"] = f"with {record['retried_with']}: {row['error']} | first: {record['first_error']}"[:300]
    return row


def phase_diagram_outputs(records, out, yields, mus, f, thumbnails=None):
    """<out>.csv, and the script's <out>.png and <out>_phi.png; with `thumbnails` (the
    folder of the points' pictures) <out>_thumbnails.png, the final wire of each point."""
    rows = [diagram_row(r) for r in records]
    write_table(out + ".csv", phase_diagram.FIELDS, rows)
    phase_diagram.draw(rows, out, yields, mus, f)
    if thumbnails is not None:
        pictures = [os.path.join(thumbnails, r.get("thumbnail") or "") for r in records]
        thumbnail_grid(rows, pictures, out + "_thumbnails.png", yields, mus, f)


def thumbnail_grid(rows, pictures, out, yields, mus, f):
    """The final wire of the lowest seed of every (yield, mu) point, yield along x and mu
    along y as in the diagram, titled with its class and phi."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(mus), len(yields), figsize=(1.5 * len(yields) + 0.6, 1.6 * len(mus) + 0.5),
                             squeeze=False)
    for i, mu in enumerate(mus):
        for j, y in enumerate(yields):
            ax = axes[len(mus) - 1 - i][j]
            ax.set_xticks([])
            ax.set_yticks([])
            here = [(int(r["seed"]), r, p) for r, p in zip(rows, pictures)
                    if abs(float(r["yield"]) - y) < 1e-9 and abs(float(r["mu"]) - mu) < 1e-9]
            if j == 0:
                ax.set_ylabel(f"mu {mu:g}", fontsize=7)
            if i == 0:
                ax.set_xlabel(f"yield {y:g}", fontsize=7)
            if not here:
                continue
            _, r, picture = min(here, key=lambda t: t[0])
            if os.path.isfile(picture):
                ax.imshow(plt.imread(picture))
            ax.set_title(f"{r['class']} {float(r['phi']):.2f}", fontsize=7)
    fig.suptitle(f"final wires, f = {f:g} (class, phi; lowest seed)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def final_wire(work):
    """The wire a 2D run left in its work folder (the checkpoint its deck writes when it
    stops), its chains joined in chain order; None without a checkpoint."""
    from sweep import newest_checkpoint
    from slender import io
    checkpoint = newest_checkpoint(work)
    if not checkpoint:
        return None
    ck = io.read_checkpoint(checkpoint)
    chains = [np.asarray(ck.chain_positions(name), dtype=float)[:, :2] for name in ck.chains]
    return chains[0] if len(chains) == 1 else np.concatenate(chains)


def crumple_measures(work, radius, npy):
    """The shape measures of scripts/crumple_study.py (outer_share, half_width) of the wire
    the run in work left; its positions go to npy (for the study's picture)."""
    pos = final_wire(work)
    if pos is None:
        return {}
    np.save(npy, pos)
    outer, half = crumple_study.shape_measures(pos, radius)
    return {"outer_share": outer, "half_width": half}


def crumple_study_outputs(records, positions, out, title, label, values, seeds):
    """<out>.csv, <out>.md and <out>.png of scripts/crumple_study.py from the points'
    records and the .npy files of their final wires, in the script's order (a row per
    seed, a column per value)."""
    by_case = {}
    for record, npy in zip(records, positions):
        var, res = record["variables"], record["result"]
        value = crumple_study.parse_value(var[record["study_variable"]])
        row = crumple_study.study_row(res, float(var["f"]), value, int(var["seed"]))
        row.update(record.get("measures", {}))
        if record["status"] != "ok":
            row.update(status="unstable", error=(record.get("error") or "?")[:200])
        pos = np.load(npy) if os.path.getsize(npy) > 0 else None
        by_case[(str(value), int(var["seed"]))] = (row, pos)
    results = [by_case[(str(crumple_study.parse_value(str(v))), int(s))] for s in seeds for v in values]
    rows = [r for r, _ in results]
    crumple_study.write_tables(rows, out, title, label, writer="workflows/crumple_study.smk")
    crumple_study.plot(results, values, seeds, out, title, label)


def first_buckle_measures(work, radius, npy):
    """scripts/first_buckle.py's measures of the buckled wire the run in work left; its
    positions go to npy (for the picture)."""
    pos = final_wire(work)
    if pos is None:
        return {}
    np.save(npy, pos)
    return first_buckle.wire_measures(pos, radius)


def first_buckle_outputs(records, positions, out, deck, feed):
    """<out>.csv and <out>.png of scripts/first_buckle.py from the points' records and the
    .npy files of their buckled wires."""
    results = []
    for record, npy in zip(records, positions):
        var = record["variables"]
        row = first_buckle.study_row(float(var["f"]), float(var["s"]), int(var["seed"]), record)
        results.append((row, np.load(npy) if os.path.getsize(npy) > 0 else None))
    first_buckle.write_outputs(results, out, deck, feed)


def packing_row(record):
    """A row of scripts/pack3d_sweep.py's table."""
    res = record["result"]
    row = {k: res[k] for k in pack3d_sweep.FIELDS if k in res}
    row.update(setup=res["case"].split("/")[-1], a_over_R=1.0 / res["R"], status="ok")
    return row


def phi_max_outputs(records, out):
    """<out>.csv, the script's <out>.png, and <out>_fit.csv: phi_max = A (a/R)^p per setup
    with three radii or more."""
    rows = [packing_row(r) for r in records]
    write_table(out + ".csv", pack3d_sweep.FIELDS, rows)
    fits = pack3d_sweep.draw(rows, out)
    write_table(out + "_fit.csv", ["setup", "A", "p"], [dict(zip(["setup", "A", "p"], f)) for f in fits])


def find_decks(examples, patterns):
    """The example decks (paths below examples/ without .lua) that run-examples would run
    for any of the patterns (none: all)."""
    return sorted({d[:-len(".lua")] for pattern in patterns or [""]
                   for d in run_examples.find_decks(examples, pattern)})


RESTART_READ = re.compile(r"""slender\.var\(\s*["']restart["']""")
LOCAL_MODULE = re.compile(r"""require\s*\(?\s*["'](lib\.[A-Za-z0-9_.]+)["']""")


def resumable(deck):
    """True if the deck (a path to its .lua) continues from a checkpoint given as
    -v restart=FILE: it, or a module it requires from its own folder (lib.scene ->
    lib/scene.lua), reads the variable "restart"."""
    folder = os.path.dirname(os.path.abspath(deck))
    with open(deck) as fh:
        text = fh.read()
    sources = [text]
    for module in LOCAL_MODULE.findall(text):
        path = os.path.join(folder, *module.split(".")) + ".lua"
        if os.path.exists(path):
            with open(path) as fh:
                sources.append(fh.read())
    return any(RESTART_READ.search(src) for src in sources)


def deck_row(deck, record):
    """A row of run-examples' table: exit status 0 is ok (a deck need not print RESULT)."""
    rc = record["returncode"]
    status = "ok" if rc == 0 else ("timeout" if record["status"] == "timeout" else f"failed ({rc})")
    return {"deck": deck + ".lua", "status": status, "wall_s": f"{record['wall_s']:.1f}",
            "headline": run_examples.headline(record["result"])}


def examples_outputs(decks, records, results, mode):
    """<results>/examples.csv and <results>/summary.md (run-examples' table, linking the
    plots each deck made in its folder <results>/decks/<deck>/)."""
    rows = [deck_row(d, r) for d, r in zip(decks, records)]
    write_table(os.path.join(results, "examples.csv"), EXAMPLE_FIELDS, rows)
    failed = sum(r["status"] != "ok" for r in rows)
    with open(os.path.join(results, "summary.md"), "w") as fh:
        fh.write(f"# Example decks ({mode} mode)\n\n| deck | status | wall s | headline | plots |\n"
                 "|---|---|---|---|---|\n")
        for deck, row in zip(decks, rows):
            pngs = sorted(os.path.relpath(os.path.join(d, f), results)
                          for d, _, files in os.walk(os.path.join(results, "decks", deck))
                          for f in files if f.endswith(".png"))
            links = " ".join(f"[{os.path.basename(p)}]({p})" for p in pngs)
            fh.write(f"| `{row['deck']}` | {row['status']} | {row['wall_s']} | {row['headline']} | {links} |\n")
        fh.write(f"\n{len(rows)} decks, {failed} failed.\n")
