# The validation report (scripts/validation_report.py as a workflow): every run of every
# case's resolution ladder (and, in the full report, its time-step ladder) is one job that
# writes one row; the report rule writes validation.md, validation.csv and the
# work-precision plots from the rows, with the script's tables, orders and checks. A row
# that exists is not run again: a case added, a deck changed (delete its rows), or a
# report cut short costs only the missing runs.
#
#   snakemake -s workflows/validation.smk --profile workflows/profiles/local
#   snakemake -s workflows/validation.smk --profile workflows/profiles/local \
#       --config 'cases=[strip_moment, sphere_pressure]' fast=true
#
# Config (workflows/config/validation.yaml, and rules/common.smk): cases (ids of
# scripts/validation_report.py; empty: all), fast (the small ladders of the CI check),
# out (where validation.md and validation/ go; default the results folder: copy them to
# docs/, or set out: docs from the repository root, to update the shipped report),
# check (true: the report rule fails when a run failed or an order is below its
# expectation, after writing the report).
import datetime
import json
import os
import sys

configfile: os.path.join(workflow.basedir, "config", "validation.yaml")

include: "rules/common.smk"

sys.path.insert(0, os.path.join(REPO, "scripts"))
import validation_report as vr
from pathlib import Path

FAST = bool(config["fast"])
CASE_IDS = list(config["cases"]) or vr.CASE_IDS
for c in CASE_IDS:
    if c not in vr.CASE_BY_ID:
        raise ValueError(f"validation: unknown case '{c}' (known: {', '.join(vr.CASE_IDS)})")
OUT = config["out"] or RESULTS
ROW = f"{RESULTS}/rows/{{case}}/{{integ}}_{{value}}.json"
DT_ROW = f"{RESULTS}/rows/{{case}}/{{integ}}_{{value}}_dt{{factor}}.json"
TIMEOUT = config["timeout"] or 3600.0


def case_rows(case_id):
    """The row files of one case, in report order."""
    case = vr.CASE_BY_ID[case_id]
    files = [ROW.format(case=case_id, integ=i, value=v) for v, i in vr.ladder(case, FAST)]
    files += [DT_ROW.format(case=case_id, integ=i, value=v, factor=f)
              for v, i, f in vr.dt_ladder(case, FAST)]
    return files


ALL_ROWS = [f for c in CASE_IDS for f in case_rows(c)]

localrules: all, report

wildcard_constraints:
    case="[a-z0-9_]+",
    integ="[a-z0-9]+",
    value="[0-9.e+-]+",
    factor="[0-9]+",


rule all:
    input:
        ALL_ROWS,
        f"{OUT}/validation.md",
        f"{OUT}/validation.csv",


def ladder_value(case, text):
    """The ladder value as the case lists it (11, 0.125), from its file-name text."""
    for v in vr.CASE_BY_ID[case]["ladder"][1] + vr.CASE_BY_ID[case]["ladder"][2]:
        if str(v) == text:
            return v
    raise ValueError(f"{case}: {text} is not on its ladder")


rule run:
    output:
        ROW,
    resources:
        **POINT_RESOURCES,
    run:
        row = vr.run_one(Path(config["slender"]).resolve(), vr.CASE_BY_ID[wildcards.case],
                         ladder_value(wildcards.case, wildcards.value), wildcards.integ, None,
                         FAST, TIMEOUT)
        with open(output[0], "w") as fh:
            json.dump(row, fh, indent=1)


rule dt_run:
    input:
        auto=ROW,
    output:
        DT_ROW,
    resources:
        **POINT_RESOURCES,
    run:
        # dt = the auto run's own step / factor; no step to divide: a row that says so
        auto = json.load(open(input.auto))
        if auto["status"] == "ok" and auto.get("dt"):
            row = vr.run_one(Path(config["slender"]).resolve(), vr.CASE_BY_ID[wildcards.case],
                             ladder_value(wildcards.case, wildcards.value), wildcards.integ,
                             auto["dt"] / int(wildcards.factor), False, TIMEOUT)
        else:
            row = {"case": wildcards.case, "status": "skipped"}
        with open(output[0], "w") as fh:
            json.dump(row, fh, indent=1)


rule report:
    input:
        ALL_ROWS,
    output:
        md=f"{OUT}/validation.md",
        csv=f"{OUT}/validation.csv",
    run:
        out = Path(OUT)
        (out / "validation").mkdir(parents=True, exist_ok=True)
        per_case, problems = [], []
        for c in CASE_IDS:
            case = vr.CASE_BY_ID[c]
            rows = [json.load(open(f)) for f in case_rows(c)]
            rows = [r for r in rows if r["status"] != "skipped"]
            ords, case_problems = vr.summarize(case, rows, FAST, out / "validation")
            per_case.append((case, rows, ords))
            problems += case_problems
        header = ["- date: %s" % datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
                  "- git: `%s`" % (vr.git_describe() or "unknown"),
                  "- made by `workflows/validation.smk` from one job per row (one 2-core "
                  "machine, one run per row; compare within a table)"]
        vr.write_outputs(out, header, per_case, FAST)
        with open(out / "problems.txt", "w") as fh:
            fh.write("".join(p + "\n" for p in problems))
        for p in problems:
            print("problem: %s" % p)
        print("validation: %d cases, %d problems" % (len(per_case), len(problems)))
        if problems and config["check"]:
            raise RuntimeError("validation: %d problems (%s/problems.txt)" % (len(problems), OUT))
