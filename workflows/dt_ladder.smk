# Does the answer depend on the time step? (scripts/dt_ladder.py as a workflow.) One
# injection deck (2D crumpling or 3D packing) runs to its jam for every rung
# (integrator:dt[:var=value...]) and seed, one job each writing one record; the table rule
# writes the script's CSV (a row per run), Markdown (seed means per rung against the first,
# the reference) and the work-precision picture.
#
#   snakemake -s workflows/dt_ladder.smk --profile workflows/profiles/local \
#       --config deck=crumple2d/classic 'vars={f: 25}' \
#       "rungs=['gear:0.000316', 'verlet:auto']" 'seeds=[1, 2, 3, 4]'
#
# Config (workflows/config/dt_ladder.yaml, and rules/common.smk): deck (below examples/),
# rungs, seeds, vars (the deck's -v variables of every run).
import json
import os
import sys

configfile: os.path.join(workflow.basedir, "config", "dt_ladder.yaml")

include: "rules/common.smk"

sys.path.insert(0, os.path.join(REPO, "scripts"))
import dt_ladder

RUNGS = list(config["rungs"])
BY_NAME = {dt_ladder.rung_name(r): r for r in RUNGS}
SEEDS = [int(s) for s in config["seeds"]]
VARIABLES = [f"{k}={sweep.lua_value(v)}" for k, v in config["vars"].items()]
POINT = f"{RESULTS}/points/{{rung}}_seed{{seed}}.json"
OUT = f"{RESULTS}/dt_ladder"

localrules: all, table

wildcard_constraints:
    rung="[A-Za-z0-9_.|+-]+",
    seed="[0-9]+",


rule all:
    input:
        expand(POINT, rung=list(BY_NAME), seed=SEEDS),
        f"{OUT}.csv",
        f"{OUT}.md",


rule point:
    output:
        POINT,
    resources:
        **POINT_RESOURCES,
    run:
        row = dt_ladder.run(os.path.abspath(config["slender"]), os.path.join(REPO, "examples"),
                            config["deck"], VARIABLES, BY_NAME[wildcards.rung], int(wildcards.seed))
        with open(output[0], "w") as fh:
            json.dump(row, fh, indent=1)


rule table:
    input:
        expand(POINT, rung=list(BY_NAME), seed=SEEDS),
    output:
        f"{OUT}.csv",
        f"{OUT}.md",
    run:
        rows = [json.load(open(f)) for f in input]
        dt_ladder.write_outputs(rows, RUNGS, SEEDS, config["deck"], VARIABLES, OUT)
