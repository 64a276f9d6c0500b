#!/usr/bin/env bash
# The study workflows on this machine (workflows/profiles/local: snakemake --cores 2),
# each with its two-point smoke config, in a temporary folder:
#  - phase diagram, pack3d phi_max, example suite, crumpling study, validation report: per-point JSON records, the tables
#    (right rows, sane values) and the plots;
#  - partial rerun: a deleted point is the only deck that runs again (dry run, then run);
#  - resume: runs cut by a timeout leave their checkpoints, and the next call continues
#    them to the same result as an uninterrupted run (pack3d points, and an example deck
#    that reads -v restart=).
#
#   tests/workflows/test_local.sh [SLENDER_BINARY]      (default: build/slender)
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
bin="$(realpath "${1:-$repo/build/slender}")"
command -v snakemake > /dev/null || { echo "workflow local: skipped (no snakemake)"; exit 0; }
[[ -x "$bin" ]] || { echo "workflow local: no slender binary at $bin" >&2; exit 1; }
export LD_LIBRARY_PATH="$(dirname "$bin")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
tmp="$(mktemp -d /tmp/slender-workflows.XXXXXX)"
trap '[[ -n "${KEEP_TMP:-}" ]] || rm -rf "$tmp"' EXIT
fail() { echo "workflow local: FAILED: $*" >&2; exit 1; }

# study NAME [snakemake args...]: the smoke config of workflows/NAME.smk in $tmp/NAME
study() {
  local name="$1"
  shift
  snakemake -s "$repo/workflows/$name.smk" --profile "$repo/workflows/profiles/local" \
    --configfile "$repo/workflows/config/${name}_smoke.yaml" --config slender="$bin" "$@" \
    --directory "$tmp/$name" > "$tmp/$name.log" 2>&1
}
check() {  # check NAME: python assertions on stdin, with results = that study's results folder
  /usr/bin/python3 - "$tmp/$1/results/$1_smoke" || { tail -n 30 "$tmp/$1.log"; fail "$1 results"; }
}

t0=$SECONDS
study phase_diagram || { tail -n 30 "$tmp/phase_diagram.log"; fail "phase_diagram"; }
check phase_diagram << 'PY'
import csv, glob, json, os, sys
results = sys.argv[1]
points = glob.glob(os.path.join(results, "points", "*.json"))
assert len(points) == 2, points
assert all(json.load(open(p))["status"] == "ok" for p in points)
rows = list(csv.DictReader(open(os.path.join(results, "phase_diagram_f10.csv"))))
assert len(rows) == 2, rows
for r in rows:
    # the smoke runs stop at max_phi = 0.3
    assert r["status"] == "ok" and 0.29 < float(r["phi"]) < 0.35 and int(r["steps"]) > 1000, r
    assert r["class"] in ("spiral", "classic", "plastic"), r
assert sorted(float(r["yield"]) for r in rows) == [0, 0.04], rows
for png in ("phase_diagram_f10.png", "phase_diagram_f10_phi.png", "phase_diagram_f10_thumbnails.png"):
    assert os.path.getsize(os.path.join(results, png)) > 1000, png
# each point's final wire, drawn from the checkpoint its run wrote when it stopped
for p in points:
    assert json.load(open(p))["thumbnail"] == os.path.basename(p)[:-5] + ".png", p
    assert os.path.getsize(p[:-5] + ".png") > 1000, p
PY
echo "phase diagram: 2 points, table and plots ($((SECONDS - t0)) s)"

# partial rerun: only the deleted point's deck runs again, then the table and plots
t0=$SECONDS
pd="$tmp/phase_diagram/results/phase_diagram_smoke/points"
kept="$pd/y0.04_mu0.4_seed1.json"
stamp="$(stat -c %Y.%y "$kept")"
rm "$pd/y0_mu0.4_seed1.json"
study phase_diagram --dry-run --quiet || fail "dry run"
grep -Eq '^point +1( |$)' "$tmp/phase_diagram.log" || { cat "$tmp/phase_diagram.log"; fail "the dry run does not plan exactly one point"; }
study phase_diagram || { tail -n 30 "$tmp/phase_diagram.log"; fail "rerun"; }
ran="$(grep -c '^rule point:' "$tmp/phase_diagram.log" || true)"
[[ "$ran" -eq 1 ]] || fail "the rerun ran $ran points, expected 1"
grep -q 'wildcards: y=0, mu=0.4, seed=1' "$tmp/phase_diagram.log" || fail "the rerun ran another point"
[[ -f "$pd/y0_mu0.4_seed1.json" && "$(stat -c %Y.%y "$kept")" == "$stamp" ]] || fail "the kept point changed"
echo "phase diagram: a deleted point reran alone ($((SECONDS - t0)) s)"

# the script is an entry point over the same workflow: the smoke grid through it gives the
# workflow's own table (the decks are deterministic), copied to --out
t0=$SECONDS
/usr/bin/python3 "$repo/scripts/phase_diagram.py" --slender "$bin" --f 10 --yields 0 0.04 --mus 0.4 --seeds 1 \
  --var max_phi=0.3 --checkpoint-every 0 --cores 2 --results "$tmp/pd_script" --out "$tmp/pd_out/pd" \
  > "$tmp/pd_script.log" 2>&1 || { tail -n 30 "$tmp/pd_script.log"; fail "scripts/phase_diagram.py"; }
/usr/bin/python3 - "$tmp" << 'PY' || fail "scripts/phase_diagram.py's table"
import csv, os, sys
tmp = sys.argv[1]
key = lambda r: {k: r[k] for k in ("yield", "mu", "seed", "class", "phi", "steps", "loops", "status")}
script = [key(r) for r in csv.DictReader(open(os.path.join(tmp, "pd_out", "pd.csv")))]
flow = [key(r) for r in csv.DictReader(open(os.path.join(tmp, "phase_diagram", "results", "phase_diagram_smoke",
                                                          "phase_diagram_f10.csv")))]
assert len(script) == 2 and script == flow, (script, flow)
for png in ("pd.png", "pd_phi.png", "pd_thumbnails.png"):
    assert os.path.getsize(os.path.join(tmp, "pd_out", png)) > 1000, png
PY
echo "phase diagram script: the workflow's table through scripts/phase_diagram.py ($((SECONDS - t0)) s)"

# resume: a 0.5 s timeout cuts both pack3d runs (about 2 s each); the next call continues them
t0=$SECONDS
if study pack3d --config slender="$bin" timeout=0.5; then fail "pack3d finished within its 0.5 s timeout"; fi
for seed in 1 2; do
  [[ -f "$tmp/pack3d/results/pack3d_smoke/work/low_torsion_R4_seed$seed/low_torsion_restart.h5" ]] ||
    { tail -n 30 "$tmp/pack3d.log"; fail "the cut run of seed $seed left no checkpoint"; }
done
study pack3d || { tail -n 30 "$tmp/pack3d.log"; fail "pack3d resumed"; }
PYTHONPATH="$repo/python" SLENDER_BIN="$bin" /usr/bin/python3 -m slender run "$repo/examples/pack3d/low_torsion.lua" \
  -v R=4 -v seed=1 -v output=false --json "$tmp/reference.json" > /dev/null || fail "the reference run"
check pack3d << PY
import csv, json, os, sys
results = sys.argv[1]
reference = json.load(open("$tmp/reference.json"))["result"]
for seed in (1, 2):
    rec = json.load(open(os.path.join(results, "points", f"low_torsion_R4_seed{seed}.json")))
    assert rec["status"] == "ok" and rec["resumed_from"] == "low_torsion_restart.h5", rec
    assert not os.path.exists(os.path.join(results, "work", f"low_torsion_R4_seed{seed}")), "work kept"
    if seed == 1:  # the engine's restart is bit-identical
        for key in ("phi", "steps", "contacts", "bend_R_over_YI"):
            assert rec["result"][key] == reference[key], (key, rec["result"][key], reference[key])
rows = list(csv.DictReader(open(os.path.join(results, "phi_max.csv"))))
assert len(rows) == 2 and all(r["setup"] == "low_torsion" and float(r["a_over_R"]) == 0.25
                              and 0.5 < float(r["phi"]) < 1 and r["stopped"] == "1" for r in rows), rows
assert os.path.getsize(os.path.join(results, "phi_max.png")) > 1000
assert os.path.exists(os.path.join(results, "phi_max_fit.csv"))
PY
echo "pack3d: 2 runs cut by a timeout, continued from their checkpoints to the uninterrupted result ($((SECONDS - t0)) s)"

# scripts/pack3d_sweep.py drives the same workflow: seed 1 through it is the workflow's row
t0=$SECONDS
/usr/bin/python3 "$repo/scripts/pack3d_sweep.py" --slender "$bin" --R 4 --seeds 1 --cores 2 \
  --results "$tmp/p3_script" --out "$tmp/p3_out/phi" > "$tmp/p3_script.log" 2>&1 ||
  { tail -n 30 "$tmp/p3_script.log"; fail "scripts/pack3d_sweep.py"; }
/usr/bin/python3 - "$tmp" << 'PY' || fail "scripts/pack3d_sweep.py's table"
import csv, os, sys
tmp = sys.argv[1]
key = lambda r: {k: r[k] for k in ("setup", "R", "seed", "phi", "steps", "contacts", "status")}
script = [key(r) for r in csv.DictReader(open(os.path.join(tmp, "p3_out", "phi.csv")))]
flow = [key(r) for r in csv.DictReader(open(os.path.join(tmp, "pack3d", "results", "pack3d_smoke", "phi_max.csv")))
        if r["seed"] == "1"]
assert len(script) == 1 and script == flow, (script, flow)
assert os.path.getsize(os.path.join(tmp, "p3_out", "phi.png")) > 1000
PY
echo "pack3d script: the workflow's row through scripts/pack3d_sweep.py ($((SECONDS - t0)) s)"

t0=$SECONDS
study examples || { tail -n 30 "$tmp/examples.log"; fail "examples"; }
check examples << 'PY'
import csv, os, sys
results = sys.argv[1]
rows = {r["deck"]: r for r in csv.DictReader(open(os.path.join(results, "examples.csv")))}
assert sorted(rows) == ["tutorial/tip_loaded_wire.lua", "validation/cantilever2d.lua"], rows
assert all(r["status"] == "ok" for r in rows.values()), rows
assert "rel_error=" in rows["validation/cantilever2d.lua"]["headline"], rows
# each deck ran in its own folder, where its outputs stay
assert os.path.exists(os.path.join(results, "decks", "tutorial", "tip_loaded_wire", "thermo.csv"))
assert "2 decks, 0 failed." in open(os.path.join(results, "summary.md")).read()
PY
echo "examples: 2 decks, summary ($((SECONDS - t0)) s)"

# run-examples --full is the same workflow in full mode (the decks' own parameters)
t0=$SECONDS
/usr/bin/python3 "$repo/scripts/run-examples" --full --slender "$bin" --out "$tmp/examples_full" \
  "validation/cantilever2d*" > "$tmp/examples_full.log" 2>&1 || { tail -n 30 "$tmp/examples_full.log"; fail "run-examples --full"; }
/usr/bin/python3 - "$tmp/examples_full" << 'PY' || fail "run-examples --full"
import json, os, sys
out = sys.argv[1]
record = json.load(open(os.path.join(out, "decks", "validation", "cantilever2d.json")))
assert record["status"] == "ok" and record["variables"] == {}, record  # no -v fast=1
summary = open(os.path.join(out, "summary.md")).read()
assert "(full mode)" in summary and "1 decks, 0 failed." in summary, summary
PY
echo "run-examples --full: the examples workflow in full mode ($((SECONDS - t0)) s)"

# the suite's long decks resume: a crumpling deck (reads -v restart=) cut by a timeout
# fails its job, leaves its state, and the next call continues it to the uninterrupted
# result; the finished deck's folder keeps its outputs but no state to continue
t0=$SECONDS
deck=(--config slender="$bin" 'decks=[crumple2d/classic.lua]' 'vars={f: 16, output: false}')
if study examples "${deck[@]}" timeout=0.8; then fail "the classic deck finished within its 0.8 s timeout"; fi
work="$tmp/examples/results/examples_smoke/decks/crumple2d/classic"
[[ -f "$work/slender_interrupted.h5" ]] || { tail -n 30 "$tmp/examples.log"; fail "the cut deck left no state"; }
study examples "${deck[@]}" || { tail -n 30 "$tmp/examples.log"; fail "examples resumed"; }
PYTHONPATH="$repo/python" SLENDER_BIN="$bin" /usr/bin/python3 -m slender run "$repo/examples/crumple2d/classic.lua" \
  -v fast=1 -v f=16 -v output=false --json "$tmp/reference_classic.json" > /dev/null || fail "the classic reference run"
check examples << PY
import json, os, sys
results = sys.argv[1]
reference = json.load(open("$tmp/reference_classic.json"))["result"]
rec = json.load(open(os.path.join(results, "decks", "crumple2d", "classic.json")))
assert rec["status"] == "ok" and rec["resumed_from"] == "slender_interrupted.h5", rec
for key in ("phi", "steps", "contacts", "loops", "ab_ratio"):  # the restart is bit-identical
    assert rec["result"][key] == reference[key], (key, rec["result"][key], reference[key])
work = os.path.join(results, "decks", "crumple2d", "classic")
assert os.path.exists(os.path.join(work, "classic_thermo.csv")), os.listdir(work)
assert not [f for f in os.listdir(work) if f.endswith(".h5")], os.listdir(work)
PY
echo "examples: a crumpling deck cut by a timeout continued from its state to the uninterrupted result ($((SECONDS - t0)) s)"
# the crumpling study: a value per column, the script's table and picture, the shape
# measures of the final wire; a run cut by a timeout continues from its checkpoint
t0=$SECONDS
study crumple_study || { tail -n 30 "$tmp/crumple_study.log"; fail "crumple_study"; }
# a deck value with an underscore (new_contacts=by_speed) is one point like any other
study crumple_study --dry-run --quiet --config variable=new_contacts 'values=[by_speed]' 'seeds=[1]' ||
  { tail -n 30 "$tmp/crumple_study.log"; fail "a value with an underscore"; }
grep -Eq '^point +1( |$)' "$tmp/crumple_study.log" ||
  { cat "$tmp/crumple_study.log"; fail "the dry run with new_contacts=by_speed does not plan one point"; }
PYTHONPATH="$repo/python" SLENDER_BIN="$bin" /usr/bin/python3 -m slender run "$repo/examples/crumple2d/classic.lua" \
  -v f=10 -v max_phi=0.3 -v damping=relative -v drag_factor=0.5 -v output=false \
  --json "$tmp/reference_study.json" > /dev/null || fail "the study's reference run"
check crumple_study << PY
import csv, json, os, sys
results = sys.argv[1]
reference = json.load(open("$tmp/reference_study.json"))["result"]
rows = list(csv.DictReader(open(os.path.join(results, "classic_f10_damping.csv"))))
assert [r["value"] for r in rows] == ["absolute", "relative"], rows
for r in rows:
    assert r["status"] == "ok" and 0.29 < float(r["phi"]) < 0.35, r
    assert 0 < float(r["outer_share"]) < 1 and 0 < float(r["half_width"]) < 1, r
    assert 1 < float(r["fractal_dimension"]) < 2, r  # the deck's D, carried into the table
relative = rows[1]
for key in ("phi", "steps", "contacts", "loops"):  # the row is the deck's RESULT
    assert float(relative[key]) == float(reference[key]), (key, relative[key], reference[key])
md = open(os.path.join(results, "classic_f10_damping.md")).read()
assert "| relative | 1 |" in md
# the per-value summary: one seed each, so the means alone (no standard error)
summary = md[md.index("Mean ± standard error"):]
assert f"| relative | 1 | {float(relative['phi']):.3f} | {float(relative['loops']):.1f} |" in summary, summary
assert os.path.getsize(os.path.join(results, "classic_f10_damping.png")) > 1000
PY
cut=(--config slender="$bin" f=16 'values=[relative]' checkpoint_every=2000)
if study crumple_study "${cut[@]}" timeout=0.8; then fail "the f = 16 study point finished within its 0.8 s timeout"; fi
ls "$tmp/crumple_study/results/crumple_study_smoke/work/vrelative_seed1/"*.h5 > /dev/null 2>&1 ||
  { tail -n 30 "$tmp/crumple_study.log"; fail "the cut study point left no checkpoint"; }
study crumple_study "${cut[@]}" || { tail -n 30 "$tmp/crumple_study.log"; fail "crumple_study resumed"; }
PYTHONPATH="$repo/python" SLENDER_BIN="$bin" /usr/bin/python3 -m slender run "$repo/examples/crumple2d/classic.lua" \
  -v f=16 -v max_phi=0.3 -v damping=relative -v drag_factor=0.5 -v output=false \
  --json "$tmp/reference_study16.json" > /dev/null || fail "the f = 16 reference run"
check crumple_study << PY
import json, os, sys
results = sys.argv[1]
reference = json.load(open("$tmp/reference_study16.json"))["result"]
rec = json.load(open(os.path.join(results, "points", "vrelative_seed1.json")))
assert rec["status"] == "ok" and rec["resumed_from"], rec
for key in ("phi", "steps", "contacts", "loops", "ab_ratio"):  # the restart is bit-identical
    assert rec["result"][key] == reference[key], (key, rec["result"][key], reference[key])
assert 0 < rec["measures"]["outer_share"] < 1, rec["measures"]
PY
echo "crumple study: 2 values, table, picture; a point cut by a timeout continued to the uninterrupted result ($((SECONDS - t0)) s)"

# the validation report: one job per row, the script's rows and orders; a run that fails
# makes the checked report fail, naming the case
t0=$SECONDS
study validation || { tail -n 30 "$tmp/validation.log"; fail "validation"; }
/usr/bin/python3 "$repo/scripts/validation_report.py" --slender "$bin" --fast --out "$tmp/validation_script" --results "$tmp/validation_script_runs" \
  --cases cantilever_small sphere_pressure > "$tmp/validation_script.log" 2>&1 ||
  { tail -n 20 "$tmp/validation_script.log"; fail "the script's report"; }
check validation << PY
import csv, os, sys
results = sys.argv[1]
key = lambda r: (r["case"], r["resolution"], r["integrator"], r["status"], r["rel_error"])
flow = [key(r) for r in csv.DictReader(open(os.path.join(results, "validation.csv")))]
script = [key(r) for r in csv.DictReader(open("$tmp/validation_script/validation.csv"))]
assert len(flow) == 6 and flow == script, (flow, script)  # the decks are deterministic
report = open(os.path.join(results, "validation.md")).read()
assert "Closed spherical shell inflated by a pressure" in report and "observed order: 1.9" in report, report
assert open(os.path.join(results, "problems.txt")).read() == ""
for case in ("cantilever_small", "sphere_pressure"):
    assert os.path.getsize(os.path.join(results, "validation", case + ".png")) > 1000, case
PY
if study validation --config slender=/bin/false results=results/validation_broken 'cases=[sphere_pressure]'; then
  fail "the checked report passed with failing runs"
fi
grep -q "sphere_pressure: 3 failed runs" "$tmp/validation/results/validation_broken/problems.txt" ||
  { tail -n 30 "$tmp/validation.log"; fail "the failed runs are not named"; }
echo "validation: 6 rows equal the script's, a failing run fails the checked report ($((SECONDS - t0)) s)"

# the shell h ladder (e-cone core radius): a row per (h, level), the deck's own numbers
t0=$SECONDS
study shell_core_radius || { tail -n 30 "$tmp/shell_core_radius.log"; fail "shell_core_radius"; }
mkdir -p "$tmp/econe_ref"
(cd "$tmp/econe_ref" && "$bin" -q "$repo/examples/shells/econe.lua" -v fast=1 -v minimizer=fire -v h=0.04 -v phi_max=1.0 \
  -v contact=0 -v plots=0 -v edge=0.25 -v refine_center=0.3 -v refine_levels=1 -v out=o > run.log 2>&1) ||
  fail "the e-cone reference run"
check shell_core_radius << PY
import csv, os, sys
results = sys.argv[1]
rows = {float(r["h"]): r for r in csv.DictReader(open(os.path.join(results, "core_radius.csv")))}
assert sorted(rows) == [0.02, 0.04] and all(r["status"] == "ok" for r in rows.values()), rows
ref = list(csv.DictReader(open("$tmp/econe_ref/o/econe.csv")))[-1]
for key in ("R_C", "R_C_s", "Eb_hat"):  # the row is the deck's last log line
    assert float(rows[0.04][key]) == float(ref[key]), (key, rows[0.04][key], ref[key])
assert all(0 < float(r["R_C"]) < 1 and int(r["triangles"]) > 0 for r in rows.values()), rows
assert os.path.getsize(os.path.join(results, "core_radius.png")) > 1000
PY
echo "shell core radius: 2 thicknesses, the deck's own numbers, table and picture ($((SECONDS - t0)) s)"

# the time-step ladder: a record per (rung, seed), the script's table; the script drives the
# same workflow and gets the same rows
t0=$SECONDS
study dt_ladder || { tail -n 30 "$tmp/dt_ladder.log"; fail "dt_ladder"; }
/usr/bin/python3 "$repo/scripts/dt_ladder.py" --slender "$bin" --deck crumple2d/classic --var f=10 \
  --var max_phi=0.3 --rung verlet:auto --rung verlet:auto:safety=0.25 --seeds 1 --cores 2 \
  --results "$tmp/dt_script" --out "$tmp/dt_out/ladder" > "$tmp/dt_script.log" 2>&1 ||
  { tail -n 30 "$tmp/dt_script.log"; fail "scripts/dt_ladder.py"; }
check dt_ladder << PY
import csv, os, sys
results = sys.argv[1]
key = lambda r: {k: r[k] for k in ("rung", "seed", "status", "phi", "steps", "loops", "contacts")}
flow = [key(r) for r in csv.DictReader(open(os.path.join(results, "dt_ladder.csv")))]
assert [r["rung"] for r in flow] == ["verlet:auto", "verlet:auto:safety=0.25"], flow
assert all(r["status"] == "ok" and 0.29 < float(r["phi"]) < 0.35 for r in flow), flow
# a quarter of the safety factor takes more steps to the same phi
assert float(flow[1]["steps"]) > 1.5 * float(flow[0]["steps"]), flow
script = [key(r) for r in csv.DictReader(open("$tmp/dt_out/ladder.csv"))]
assert script == flow, (script, flow)
assert "| verlet:auto | 1 (0) |" in open(os.path.join(results, "dt_ladder.md")).read()
assert os.path.getsize("$tmp/dt_out/ladder.png") > 1000
PY
echo "dt ladder: 2 rungs, the script's table through the workflow ($((SECONDS - t0)) s)"
echo "workflow local: ok"
