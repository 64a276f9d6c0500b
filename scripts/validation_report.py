#!/usr/bin/python3
"""Error against run time for every physics family slender ships: one report.

Runs every validation case over its ladder of resolutions (nodes, cells, mesh edge),
integrators and time steps, and writes

    OUT/validation.md     per case: the reference and its source, a table (resolution,
                          dt, relative error, wall time, throughput), the observed
                          convergence order, and a log-log work-precision PNG
    OUT/validation.csv    every run
    OUT/validation/<case>.png

The default OUT is docs/ (the report is docs/validation.md). --fast runs small ladders
and checks that each case's error falls with at least its expected order (the CI test
validation.fast_orders); it never asserts a time. Exit status: 0 ok, 1 a run failed or an
order is below its expectation, 2 usage error.

    /usr/bin/python3 scripts/validation_report.py               # the full report (about 1 h)
    /usr/bin/python3 scripts/validation_report.py --fast --out /tmp/v
    /usr/bin/python3 scripts/validation_report.py --cases plate_ss cylinder
    /usr/bin/python3 scripts/validation_report.py --cases michell --keep   # rerun one case

--keep takes the rows of the cases not rerun from the existing OUT/validation.csv, so the
report still covers every case.

A command-line entry point over workflows/validation.smk (workflows/README.md): one job per
run, resumable (a row already in --results is not run again: delete a case's rows after
changing its deck), --cores at a time (default 1, so that the wall times are those of a
quiet machine), --profile slurm for a cluster. The functions below run one row, fit the
orders and write the report; the workflow imports them.
"""
import argparse
import csv
import datetime
import math
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "python"))
sys.path.insert(0, str(REPO / "scripts"))
from slender.run import run_deck  # noqa: E402

EX = REPO / "examples"


def to_float(value):
    """float(value), or None if it is not a number."""
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def md_escape(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def git_describe():
    try:
        return subprocess.run(["git", "-C", str(REPO), "describe", "--always", "--dirty"],
                              capture_output=True, text=True, timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""
THEORY_KISS = 7.08  # docs/models.md §7.1 A-1: phi_e^kiss -> 7.08 as h -> 0


def nodes_h(n):  # a chain of n nodes on a unit length: segment length
    return 1.0 / (int(n) - 1)


def spiral_metric(work, result):
    """Median |E_b - model| / E_b of the spiral scene against the corrected §2.8 model."""
    import numpy as np
    import crumple_stats as cs
    rows = [r for r in cs.read([str(work / "spiral_thermo.csv")]) if "energy.bend" in r]
    phi = np.array([r["feed.phi"] for r in rows])
    E = np.array([r["energy.bend"] for r in rows])
    keep = phi > 0
    phi, E = phi[keep], E[keep]
    R = float(result.get("f", 10))
    m = cs.spiral_model(phi, R, 1.0, 60.0, False)
    hi = phi <= 0.75
    C = float(np.mean(E[hi] - m[hi]))  # the constant of the model, by least squares
    rel = np.abs(E - m - C) / np.maximum(np.abs(E), 1e-300)
    sel = hi & (E > 0.05 * E.max())
    return float(np.median(rel[sel])), "phi up to %.2f" % phi.max()


def spool_metric(work, result):
    """Median |E_b - E_Purohit| / E_Purohit of the ordered (low-torsion) packing for
    0.1 <= phi <= 0.3, where the inverse spool holds."""
    import numpy as np
    import pack3d_stats as ps
    with open(work / "low_torsion_thermo.csv") as fh:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(fh)]
    R = float(result["R"])
    YI = math.pi * 1000 / 4
    phi = np.array([r["feed.phi"] for r in rows])
    eb = np.array([r["energy.bend"] for r in rows]) * R / YI
    _, model, _, _ = ps.purohit(phi, R)
    sel = (phi >= 0.1) & (phi <= 0.3) & np.isfinite(model)
    if sel.sum() < 3:
        raise RuntimeError("fewer than 3 samples with 0.1 <= phi <= 0.3")
    rel = np.abs(eb[sel] - model[sel]) / model[sel]
    return float(np.median(rel)), "%d samples" % sel.sum()


# Each case: a deck, fixed -v values, a ladder (name, full values, fast values), the
# resolution's length scale h(value) for the observed order, the integrators, the
# reference and its source, the order expected of the fast ladder (None: not checked),
# and an optional metric(work_dir, result) -> (rel_error, note) instead of rel_error.
CASES = [
    dict(id="cantilever_small", family="wire 2D", title="2D cantilever, small deflection",
         deck="validation/cantilever2d.lua", fixed={"alpha": 0.01, "model": "bend2d"},
         ladder=("nodes", [11, 21, 41, 81], [11, 21, 41]), h=nodes_h,
         integrators=(["verlet", "gear5", "fire", "newton"], ["fire"]), order=1.8,
         reference="tip deflection of the extensible elastica with the wire's EA (shooting on "
                   "theta'(0), RK4 + bisection, in the deck); alpha = PL^2/EI = 0.01, where it "
                   "equals Euler-Bernoulli PL^3/3EI to 1e-4",
         source="Timoshenko & Gere, Theory of Elastic Stability, §2; docs/models.md §2.1"),
    dict(id="cantilever_large", family="wire 2D", title="2D cantilever, large deflection",
         deck="validation/cantilever2d.lua", fixed={"alpha": 3, "model": "bend2d"},
         ladder=("nodes", [11, 21, 41, 81], [11, 21, 41]), h=nodes_h,
         integrators=(["verlet", "gear5", "fire", "newton"], ["fire"]), order=1.8, dt_ladder=True,
         reference="tip position of the extensible elastica at alpha = 3 (shooting, in the deck; "
                   "scripts/elastica.py re-derives it independently to 1e-10)",
         source="Bisshopp & Drucker, Q. Appl. Math. 3 (1945) 272; docs/models.md §2.1"),
    dict(id="buckling_pinned_2d", family="wire 2D", title="2D Euler buckling, pinned-pinned",
         deck="validation/buckling2d.lua", fixed={"bc": "pinned", "model": "bend2d"},
         ladder=("nodes", [11, 21, 41], [11, 21]), h=nodes_h,
         integrators=(["fire"], ["fire"]), order=1.8,
         reference="critical load pi^2 EI / L^2 (bisection over runs, bracket 1.5e-5)",
         source="Euler (1744); Timoshenko & Gere §2.2"),
    dict(id="buckling_clamped_2d", family="wire 2D", title="2D Euler buckling, clamped-free",
         deck="validation/buckling2d.lua", fixed={"bc": "clamped", "model": "bend2d"},
         ladder=("nodes", [11, 21, 41], [11, 21]), h=nodes_h,
         integrators=(["fire"], ["fire"]), order=1.6,
         reference="critical load pi^2 EI / (4 L^2)", source="Timoshenko & Gere §2.1"),
    dict(id="buckling_clamped_3d", family="rod 3D", title="3D Euler buckling, clamped-free, discrete elastic rod",
         deck="validation/buckling2d.lua", fixed={"bc": "clamped", "model": "rod3d"},
         ladder=("nodes", [11, 21, 41], [11, 21]), h=nodes_h,
         integrators=(["fire"], ["fire"]), order=1.6,
         reference="critical load pi^2 YI / (4 L^2)", source="Timoshenko & Gere §2.1; docs/models.md §3"),
    dict(id="buckling_clamped_cosserat", family="rod 3D",
         title="3D Euler buckling, clamped-free, quaternion Cosserat rod",
         deck="validation/buckling2d.lua",
         fixed={"bc": "clamped", "model": "cosserat", "coupling_factor": 10},
         ladder=("nodes", [11, 21, 41], [11, 21]), h=nodes_h,
         integrators=(["static"], ["static"]), order=1.2,
         reference="critical load pi^2 YI / (4 L^2). Each trial relaxes the straight column under "
                   "P and tests the sign of the lowest eigenvalue of its stiffness matrix "
                   "(sim:lowest_stiffness), the exact critical load of the discrete rod; trials "
                   "that watch a perturbation grow or decay over a fixed time or FIRE budget "
                   "moved this result by about 1e-3. The coupling C acts like a shear "
                   "compliance: at C = EA the error stops at 9e-4 from 21 nodes on, the report "
                   "uses C = 10 EA (floor about 1e-4)",
         source="Timoshenko & Gere §2.1; docs/models.md §4"),
    dict(id="cantilever_rod3d", family="rod 3D", title="3D cantilever (alpha = 3), discrete elastic rod",
         deck="validation/cantilever2d.lua", fixed={"alpha": 3, "model": "rod3d"},
         ladder=("nodes", [11, 21, 41], [11, 21]), h=nodes_h,
         integrators=(["fire", "newton"], ["fire"]), order=1.6,
         reference="the 2D elastica tip position (the rod bends in a plane)",
         source="as the 2D cantilever; docs/models.md §3"),
    dict(id="cantilever_cosserat", family="rod 3D", title="3D cantilever (alpha = 3), quaternion Cosserat rod",
         deck="validation/cantilever2d.lua", fixed={"alpha": 3, "model": "cosserat", "coupling_factor": 10},
         fast_fixed={"coupling_factor": 1},
         ladder=("nodes", [11, 21, 41], [11, 21]), h=nodes_h,
         integrators=(["gear5"], ["gear5"]), order=1.2,
         reference="the 2D elastica tip position. The coupling C (t - d3)^2 acts like a shear "
                   "compliance, an error floor that falls as 1/C: with C = EA the error stops at "
                   "6e-4 to 9e-4 from 21 nodes on; the report uses C = 10 EA (the fast check EA)",
         source="as the 2D cantilever; docs/models.md §4"),
    dict(id="michell", family="rod 3D", title="Michell's instability of a twisted ring (Cosserat rod)",
         deck="validation/michell.lua", fixed={"iterations": 14, "criterion": "static"},
         fast_fixed={"iterations": 8},
         ladder=("nodes", [12, 24, 48, 96], [12, 24]), h=lambda n: 1.0 / int(n),
         integrators=(["static"], ["static"]), order=1.5,
         reference="critical total twist theta_c = 2 pi sqrt(3) YI / GJ of a closed naturally "
                   "straight ring (bisection over runs; each relaxes the planar ring and tests the "
                   "sign of the lowest eigenvalue of its stiffness matrix; the damped-dynamics "
                   "trials of -v criterion=dynamic gave 1.3e-1 / 3.5e-3 / 8.5e-4 at 12 / 24 / 48 "
                   "nodes in minutes)",
         source="Michell, Messenger of Math. 19 (1889) 181; Goriely, J. Elasticity 84 (2006) 281; docs/models.md §7.1 A-2"),
    dict(id="continuation_column", family="wire 2D",
         title="2D Euler buckling, clamped-free, by continuation (Newton statics)",
         deck="validation/continuation.lua", fixed={"case": "column"},
         ladder=("nodes", [11, 21, 41, 81], [11, 21]), h=nodes_h,
         integrators=(["none"], ["none"]), order=1.8,
         reference="critical load pi^2 EI / (4 L^2): the load where the count of negative pivots "
                   "of the stiffness matrix changes along the straight column's path, bisected on "
                   "the arc length (one run, no trials); below about 1e-5 the extensible column's "
                   "own shift P/EA shows",
         source="Timoshenko & Gere §2.1; docs/models.md §9.4"),
    dict(id="continuation_branch", family="wire 2D",
         title="2D buckled column (elastica) by branch switching",
         deck="validation/continuation.lua", fixed={"case": "column", "branch": "true"},
         ladder=("nodes", [11, 21, 41, 81], [11, 21]), h=nodes_h,
         integrators=(["none"], ["none"]), order=1.8,
         metric=lambda work, r: (float(r["branch_error"]),
                                 "%s points checked on the branch" % r["branch_points"]),
         reference="lambda / P_cr = (2 K(k) / pi)^2 at the tip deflection delta / L = 2 k / K(k) "
                   "(inextensible elastica), largest error over the branch up to delta = 0.55 L",
         source="Timoshenko & Gere §2.7; docs/models.md §9.4"),
    dict(id="continuation_roll", family="wire 2D",
         title="2D wire rolled into a full circle by an end moment",
         deck="validation/continuation.lua", fixed={"case": "roll"},
         ladder=("nodes", [11, 21, 41, 81], [11, 21]), h=nodes_h,
         integrators=(["none"], ["none"]), order=1.8,
         metric=lambda work, r: (max(float(r["arc_error"]), float(r["closure_gap"])),
                                 "closure gap %.2e" % float(r["closure_gap"])),
         reference="tip on the exact arc (sin kL / k, (1 - cos kL) / k), k = M / EI, along the "
                   "whole continuation path, and back at the root at M = 2 pi EI / L (error per "
                   "length L)",
         source="pure bending; docs/models.md §9.5"),
    dict(id="continuation_tip", family="wire 2D",
         title="Displacement control: a cantilever's tip driven down by a prescribed motion",
         deck="validation/continuation.lua", fixed={"case": "tip"},
         ladder=("nodes", [11, 21, 41, 81], [11, 21]), h=nodes_h,
         integrators=(["none"], ["none"]), order=1.8,
         reference="reaction of the held tip at w < 0.01 L against the Euler-Bernoulli tip force "
                   "3 EI w / L^3 (fix prescribe walked by sim:continuation to w = 0.3 L, no "
                   "critical point on the way)",
         source="Euler-Bernoulli cantilever; docs/models.md §9.8"),
    dict(id="plate_ss", family="shell", title="Square plate under uniform load, simply supported",
         deck="validation/plate_load.lua", fixed={"support": "simply_supported"},
         ladder=("n", [8, 16, 32], [8, 16]), h=lambda n: 1.0 / int(n),
         integrators=(["fire", "lbfgs", "newton"], ["lbfgs"]), order=1.5,
         reference="centre deflection alpha q a^4 / D, alpha = 0.00406235 (Navier series summed in the deck)",
         source="Timoshenko & Woinowsky-Krieger, Theory of Plates and Shells, §30 eq. 139"),
    dict(id="plate_clamped", family="shell", title="Square plate under uniform load, clamped",
         deck="validation/plate_load.lua", fixed={"support": "clamped"},
         ladder=("n", [8, 16, 32], [8, 16]), h=lambda n: 1.0 / int(n),
         integrators=(["fire", "lbfgs", "newton"], ["lbfgs"]), order=0.8,
         reference="centre deflection 0.00126532 q a^4 / D; first order: the clamp fixes "
                   "the three rows of nodes of docs/models.md §6.7",
         source="Timoshenko & Woinowsky-Krieger, Table 35; Taylor & Govindjee (2004) for the digits"),
    dict(id="plate_clamped_edges", family="shell",
         title="Square plate under uniform load, clamped edges at second order (Newton)",
         deck="validation/plate_load.lua", fixed={"support": "clamped_edges"},
         ladder=("n", [8, 16, 32, 64], [8, 16]), h=lambda n: 1.0 / int(n),
         integrators=(["newton"], ["newton"]), order=1.5,
         reference="centre deflection 0.00126532 q a^4 / D; `clamped_edges`: boundary nodes held, "
                   "each ghost the reflection of its partner's displacement (docs/models.md §6.7)",
         source="Taylor & Govindjee, Commun. Numer. Meth. Engng 20 (2004) 757"),
    dict(id="strip_shear", family="shell",
         title="Cantilever shell strip under an end shear, large deflection (Newton)",
         deck="validation/shell_strip.lua", fixed={},
         ladder=("n", [2, 4, 8, 16], [2, 4]), h=lambda n: 1.0 / int(n),
         integrators=(["none"], ["none"]), order=1.5,
         reference="tip (-u, w) = (3.289, 6.700) for P L^2 / EI = 4: the extensible elastica with "
                   "the strip's EA (shooting, in the deck); error |tip - elastica| / L; root edge "
                   "`clamped_edges`, the end shear a `line_load` on the tip edge",
         source="Timoshenko & Gere §2.7; the statics issue's shell obstacle course; docs/models.md §6.7"),
    dict(id="strip_moment", family="shell",
         title="Cantilever shell strip rolled up by an end moment, arc-length continuation",
         deck="validation/shell_strip.lua", fixed={"load": "moment"},
         ladder=("n", [2, 4, 8, 16], [2, 4]), h=lambda n: 1.0 / int(n),
         integrators=(["none"], ["none"]), order=1.5,
         reference="M = 2 pi EI / L as a `line_moment` on the tip edge, followed from lambda = 0 to 1 "
                   "by `sim:continuation`; error: the largest |tip - reference| / L over the path. "
                   "Reference: the rolled Koiter strip (uniform stretch s and rotation rate k, "
                   "E h (s^2 - 1)/2 = -D k^2, D s^2 k = m), which turns 6.6e-4 further than the "
                   "linear elastica's full circle at lambda = 1; the nodes keep their y (planar path)",
         source="the statics issue's shell obstacle course; docs/models.md §6.4"),
    dict(id="sphere_pressure", family="shell",
         title="Closed spherical shell inflated by a pressure (Newton)",
         deck="validation/shell_sphere_pressure.lua", fixed={},
         ladder=("level", [1, 2, 3, 4], [1, 2, 3]), h=lambda l: 2.0 ** (1 - int(l)),
         integrators=(["none"], ["none"]), order=1.5,
         reference="uniform inflation of a Koiter sphere: 2 (1 + nu) (C_m e r - C_b b) = p r^2 with "
                   "e = ((r/R)^2 - 1)/2, b = -(r - R)/R^2 (R = 1, h = 0.01, Y = 1e4, nu = 0.3, p = 3: "
                   "w = 0.0105550); the radius read from the enclosed volume",
         source="membrane theory of shells (Timoshenko & Woinowsky-Krieger §14); docs/models.md §6.4"),
    dict(id="scordelis_lo", family="shell",
         title="Scordelis-Lo roof: cylindrical shell on rigid diaphragms under self weight (Newton)",
         deck="validation/scordelis_lo.lua", fixed={},
         ladder=("n", [4, 8, 16, 32, 64], [8, 16]), h=lambda n: 1.0 / int(n),
         integrators=(["none"], ["none"]), order=1.5,
         reference="vertical deflection 0.3006 at the middle of a free edge (linear Kirchhoff-Love; "
                   "R = 25, L = 50, +-40 degrees, t = 0.25, E = 4.32e8, nu = 0, weight 90 per area); "
                   "ends `diaphragm_edges`, free edges `free_ghosts`, the load scaled by 1e-3 for the "
                   "linear response; the reference has four digits (1.7e-4)",
         source="MacNeal & Harder, Finite Elem. Anal. Des. 1 (1985) 3; Kiendl et al., CMAME 198 "
                "(2009) 3902 for the Kirchhoff-Love value"),
    dict(id="cylinder", family="shell", title="Cylindrical bending of a Koiter shell",
         deck="validation/cylinder_bend.lua", fixed={},
         ladder=("n", [8, 16, 32, 64], [8, 16, 32]), h=lambda n: 1.0 / int(n),
         integrators=(["none"], ["none"]), order=1.8,
         reference="bending energy D kappa^2 A / 2 of a strip wrapped isometrically on a cylinder",
         source="Timoshenko & Woinowsky-Krieger §2"),
    dict(id="econe_kiss", family="shell", title="E-cone kissing angle (h = 0.02) against vanishing thickness",
         deck="shells/econe.lua", fixed={"h": 0.02, "phi_max": 7.0}, fast_fixed={"fast": 1},
         ladder=("edge", [0.125, 0.0625, 0.03125], [0.125]), h=float,
         integrators=(["fire"], ["fire"]), order=None,
         metric=lambda work, r: (abs(float(r["phi_kiss"]) - THEORY_KISS) / THEORY_KISS,
                                 "phi_kiss = %s" % r["phi_kiss"]),
         reference="phi_e^kiss -> 7.08 as h -> 0 (vanishing-thickness theory); at h = 0.02 the "
                   "difference mixes discretisation with the finite thickness, and the uniform "
                   "meshes under-resolve the core (refine_center/refine_levels refine it)",
         source="docs/models.md §7.1 A-1 and §7.2 S-1"),
    dict(id="spiral_energy", family="wire 2D", title="Spiral-phase bending energy against its analytic model",
         deck="crumple2d/spiral.lua", fixed={"output": "false"},
         ladder=("f", [10], [10]), h=lambda f: 1.0 / float(f),
         fast_fixed={"fast": 1}, integrators=(["gear5"], ["gear5"]), order=None, metric=spiral_metric,
         reference="E_b(phi) = E_core + pi YI/d ln(R/R_c) + C (the corrected §2.8 model, C by least "
                   "squares), median relative deviation for phi <= 0.75",
         source="docs/models.md §2.8, §7.1 A-3"),
    dict(id="spool", family="rod 3D", title="Ordered 3D packing against the inverse spool",
         deck="pack3d/low_torsion.lua", fixed={"output": "false"},
         ladder=("R", [5], [4]), h=lambda R: 1.0 / float(R),
         integrators=(["gear6"], ["gear6"]), order=None, metric=spool_metric,
         reference="bending energy E_b R / YI of Purohit's inverse spool (d_s = 2.81 a), median "
                   "relative deviation for 0.1 <= phi <= 0.3",
         source="Purohit, Kondev & Phillips, PNAS 100 (2003) 3173; docs/models.md §5.4"),
]
CASE_IDS = [c["id"] for c in CASES]


def run_one(slender, case, value, integ, dt, fast, timeout):
    """Runs one deck; returns a row dict (status ok or an error)."""
    ov = dict(case["fixed"])
    if fast:
        ov.update(case.get("fast_fixed", {}))
    ov[case["ladder"][0]] = value
    if integ != "none":
        ov["integrator"] = integ
    if dt is not None:
        ov["dt"] = repr(dt)
    row = {"case": case["id"], "resolution": value, "integrator": integ,
           "dt_mode": "auto" if dt is None else "set"}
    with tempfile.TemporaryDirectory(prefix="slender_val_") as tmp:
        res = run_deck(EX / case["deck"], ov, cwd=tmp, timeout=timeout, binary=slender)
        row["cmd"] = " ".join(shlex.quote(c) for c in res.command)
        row["run_s"] = res.wall_s
        results = res.results
        if res.returncode != 0 or not results:
            row["status"] = "failed"
            row["error"] = res.error
            return row
        r = results[-1]
        row["status"] = "ok"
        row["wall_s"] = to_float(r.get("wall_s")) or row["run_s"]
        row["dt"] = to_float(r.get("dt"))
        row["throughput"] = to_float(r.get("node_steps_per_s"))
        row["throughput_kind"] = "node"
        if row["throughput"] is None and r.get("element_steps_per_s"):
            row["throughput"] = to_float(r.get("element_steps_per_s"))
            row["throughput_kind"] = "element"
        try:
            if "metric" in case:
                row["rel_error"], row["note"] = case["metric"](Path(tmp), r)
            else:
                row["rel_error"] = to_float(r.get("rel_error"))
        except Exception as e:  # a post-processing failure is a failed run, reported
            row["status"] = "failed"
            row["error"] = "post-processing: %s" % e
    return row


def orders(case, rows):
    """Observed order between consecutive resolutions of one integrator's auto-dt runs."""
    ok = [r for r in rows if r["status"] == "ok" and r["dt_mode"] == "auto" and r["rel_error"]]
    ok.sort(key=lambda r: -case["h"](r["resolution"]))
    out = []
    for a, b in zip(ok, ok[1:]):
        ha, hb = case["h"](a["resolution"]), case["h"](b["resolution"])
        if a["rel_error"] > 0 and b["rel_error"] > 0 and ha != hb:
            out.append(math.log(a["rel_error"] / b["rel_error"]) / math.log(ha / hb))
    return out


def plot(path, case, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.2, 3.9))
    for integ in sorted({r["integrator"] for r in rows}):
        pts = sorted((r["wall_s"], r["rel_error"]) for r in rows
                     if r["integrator"] == integ and r["status"] == "ok" and r["rel_error"])
        if pts:
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", ms=4,
                      label=integ if integ != "none" else "energy evaluation")
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("relative error")
    ax.set_title(case["title"], fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def g(v, f="%.3g"):
    return "" if v is None or v == "" else f % v


def write_report(out, header, per_case, fast):
    lines = ["# Validation: error against run time", ""]
    lines += ["Generated by `scripts/validation_report.py%s`; do not edit by hand." %
              (" --fast" if fast else ""), ""] + header + [""]
    lines += ["Every case compares one observable with an analytic or published reference. "
              "Wall time is the deck's own measurement of the physics (not start-up); "
              "throughput is node-steps per second where the deck reports it. The observed "
              "order is log(e_i / e_i+1) / log(h_i / h_i+1) between consecutive resolutions "
              "(h: segment length, cell size or mesh edge).", ""]
    lines += ["## Summary: the best error per case and what it cost", "",
              "| family | case | best rel. error | at | wall s | observed order | expected |",
              "|---|---|---|---|---|---|---|"]
    for case, rows, ords in per_case:
        ok = [r for r in rows if r["status"] == "ok" and r["rel_error"] is not None]
        if not ok:
            lines.append("| %s | %s | (failed) | | | | |" % (case["family"], case["title"]))
            continue
        best = min(ok, key=lambda r: (r["rel_error"], r["wall_s"]))
        lines.append("| %s | %s | %.2e | %s = %s, %s | %.3g | %s | %s |" % (
            case["family"], case["title"], best["rel_error"], case["ladder"][0],
            best["resolution"], best["integrator"], best["wall_s"],
            ", ".join("%.2f" % o for o in ords) or "-",
            "%.1f" % case["order"] if case["order"] else "-"))
    lines.append("")
    for case, rows, ords in per_case:
        lines += ["## %s" % case["title"], "",
                  "- reference: %s" % case["reference"], "- source: %s" % case["source"],
                  "- deck: `examples/%s`" % case["deck"],
                  "- observed order: %s" % (", ".join("%.2f" % o for o in ords) or "-"), "",
                  "| %s | integrator | dt | rel. error | wall s | %s-steps/s | note |" % (
                      case["ladder"][0], "element" if case["family"] == "shell" else "node"),
                  "|---|---|---|---|---|---|---|"]
        for r in rows:
            if r["status"] != "ok":
                lines.append("| %s | %s | | failed | | | %s |" % (
                    r["resolution"], r["integrator"], md_escape(r.get("error", ""))[:120]))
                continue
            lines.append("| %s | %s | %s%s | %s | %s | %s | %s |" % (
                r["resolution"], r["integrator"], g(r.get("dt"), "%.3g"),
                "" if r["dt_mode"] == "auto" else " (set)", g(r["rel_error"], "%.2e"),
                g(r["wall_s"]), g(r.get("throughput"), "%.2e"), r.get("note", "")))
        lines += ["", "![%s](validation/%s.png)" % (case["id"], case["id"]), ""]
    lines += holdings_section()
    (out / "validation.md").write_text("\n".join(lines) + "\n")


def holdings_section():
    """What each example scene holds, from the expectations the example suite checks
    (tests/decks/inventory.json, compared with slender --inventory in examples.fast_suite)."""
    import json
    path = REPO / "tests" / "decks" / "inventory.json"
    if not path.is_file():
        return []
    inv = json.loads(path.read_text())
    lines = ["## What each example scene holds", "",
             "A scene allocates only what its styles use. The example suite checks every deck "
             "against this list (`slender --inventory`, test `examples.fast_suite`); node "
             "properties beyond position, velocity, force and mass, extra coordinates, "
             "neighbour structures and style families:", "",
             "| deck | node properties | coordinates | neighbours | families |", "|---|---|---|---|---|"]
    core = {"position", "velocity", "force", "mass"}
    for deck in sorted(inv):
        h = inv[deck]
        props = [p for p in h["node_properties"] if p not in core]
        fams = sorted({s.split()[0] for s in h["styles"]})
        lines.append("| `%s` | %s | %s | %s | %s |" % (
            deck, ", ".join(props) or "-", ", ".join(h["coordinates"]) or "-",
            ", ".join(h["neighbor"]) or "none", ", ".join(fams)))
    return lines + [""]


CASE_BY_ID = {c["id"]: c for c in CASES}
CSV_COLUMNS = ["case", "resolution", "integrator", "dt_mode", "dt", "rel_error", "wall_s",
               "throughput", "status", "note", "error", "run_s", "cmd"]


def ladder(case, fast):
    """The runs of a case's resolution ladder, in report order: (value, integrator)."""
    values = case["ladder"][2 if fast else 1]
    integs = case["integrators"][1 if fast else 0]
    return [(v, integ) for integ in integs for v in values]


def dt_ladder(case, fast):
    """The time-step ladder of a case (full report only): the finest resolution with each
    dynamic integrator at dt = auto / factor; (value, integrator, factor)."""
    if not case.get("dt_ladder") or fast:
        return []
    values = case["ladder"][1]
    return [(values[-1], integ, f) for integ in case["integrators"][0]
            if integ not in ("fire", "newton") for f in (2, 4)]


def summarize(case, rows, fast, plot_dir=None):
    """The observed orders of a case's rows (those of its last integrator) and its problems;
    draws its work-precision plot into plot_dir."""
    integs = list(dict.fromkeys(r["integrator"] for r in rows))
    main_ords = orders(case, [r for r in rows if r["integrator"] == integs[-1]]) if integs else []
    problems = []
    if any(r["status"] != "ok" for r in rows):
        problems.append("%s: %d failed runs" % (case["id"], sum(r["status"] != "ok" for r in rows)))
    if fast and case["order"] and main_ords and main_ords[-1] < case["order"]:
        problems.append("%s: observed order %.2f below the expected %.1f" %
                        (case["id"], main_ords[-1], case["order"]))
    if plot_dir is not None:
        plot(Path(plot_dir) / ("%s.png" % case["id"]), case, rows)
    return main_ords, problems


def write_outputs(out, header, per_case, fast):
    """OUT/validation.md and OUT/validation.csv from (case, rows, orders) triples."""
    write_report(out, header, per_case, fast)
    with open(out / "validation.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=CSV_COLUMNS, extrasaction="ignore")
        w.writeheader()
        for _, rows, _ in per_case:
            w.writerows(rows)


def read_rows(path):
    """The rows of a report's validation.csv by case, numbers as floats."""
    kept = {}
    with open(path) as fh:
        for r in csv.DictReader(fh):
            for k in ("dt", "rel_error", "wall_s", "throughput", "run_s"):
                r[k] = to_float(r.get(k)) if r.get(k) not in (None, "") else None
            kept.setdefault(r["case"], []).append(r)
    return kept


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--slender", default=str(REPO / "build" / "slender"))
    p.add_argument("--out", default=str(REPO / "docs"), help="writes OUT/validation.md and OUT/validation/")
    p.add_argument("--fast", action="store_true", help="small ladders; check the expected orders")
    p.add_argument("--cases", nargs="+", choices=CASE_IDS, default=CASE_IDS)
    p.add_argument("--timeout", type=float, default=3600.0, help="seconds per run")
    p.add_argument("--keep", action="store_true",
                   help="keep the other cases' rows from the existing OUT/validation.csv")
    p.add_argument("--results", default=None,
                   help="the workflow's folder of one record per run (default results/validation, "
                        "or results/validation_fast with --fast, in the repository); rows already "
                        "there are not run again")
    p.add_argument("--cores", type=int, default=1,
                   help="runs at a time (1: the wall times of the report are those of a quiet machine)")
    p.add_argument("--profile", default="local", choices=["local", "slurm"])
    p.add_argument("--dry-run", action="store_true", help="print what would run and exit")
    args = p.parse_args(argv)
    slender = Path(args.slender).resolve()
    if not slender.is_file():
        print("error: no slender at %s" % slender, file=sys.stderr)
        return 2
    out = Path(args.out).resolve()
    results = Path(args.results or REPO / "results" / ("validation_fast" if args.fast else "validation")).resolve()
    kept = read_rows(out / "validation.csv") if args.keep and (out / "validation.csv").is_file() else {}
    kept = {c: rows for c, rows in kept.items() if c not in args.cases}
    # the workflow writes the report of the cases run; with rows kept it goes to the
    # results folder, and the merged report to OUT below
    made = results / "report" if kept else out
    started = datetime.datetime.now()
    cmd = ["snakemake", "-s", str(REPO / "workflows" / "validation.smk"),
           "--profile", str(REPO / "workflows" / "profiles" / args.profile),
           "--directory", str(REPO), "--cores", str(args.cores), "--config",
           "slender=%s" % slender, "results=%s" % results, "out=%s" % made,
           "cases=[%s]" % ", ".join(args.cases), "fast=%s" % args.fast,  # True / False: Snakemake's booleans
           "check=True", "timeout=%g" % args.timeout]
    if args.dry_run:
        cmd += ["--dry-run", "--quiet"]
    else:
        # the report is made again whenever asked, from the rows there are (a forced rule
        # whose job Snakemake spawns in a second process would find its outputs present)
        for name in ("validation.md", "validation.csv"):
            if (made / name).is_file():
                (made / name).unlink()
    print(" ".join(shlex.quote(c) for c in cmd), flush=True)
    done = subprocess.run(cmd).returncode
    if args.dry_run or not kept:
        return done
    if not (made / "validation.csv").is_file():
        return done or 1
    # merged: the rows just made, and the kept rows of the other cases, in report order
    new = read_rows(made / "validation.csv")
    per_case, problems = [], []
    for case in CASES:
        rows = new.get(case["id"]) or kept.get(case["id"])
        if not rows:
            continue
        ords, case_problems = summarize(case, rows, args.fast, out / "validation" if case["id"] in new else None)
        problems += case_problems if case["id"] in new else []
        per_case.append((case, rows, ords))
    (out / "validation").mkdir(parents=True, exist_ok=True)
    header = ["- date: %s" % started.strftime("%Y-%m-%d %H:%M"),
              "- git: `%s`" % (git_describe() or "unknown"),
              "- made by `workflows/validation.smk` from one job per row (one 2-core machine, one run "
              "per row; compare within a table)",
              "- rows of the cases not rerun kept from the previous report (--keep): %s" % ", ".join(kept)]
    write_outputs(out, header, per_case, args.fast)
    print("wrote %s" % (out / "validation.md"))
    print("validation: %d cases, %d problems" % (len(per_case), len(problems)))
    return done or (1 if problems else 0)


if __name__ == "__main__":
    sys.exit(main())
