# Maximum packing fraction against a/R (scripts/pack3d_sweep.py as a workflow): every
# (setup, sphere radius R, seed) of the config's grid runs examples/pack3d/<setup>.lua
# to its stop force, one job each; the table and the plot with its power-law fits are
# those of the script (its draw, through lib/studies.py).
#
#   snakemake -s workflows/pack3d.smk --profile workflows/profiles/local
#
# Config (workflows/config/pack3d.yaml, and rules/common.smk): setups, R, seeds;
# checkpoint_every (steps between a run's checkpoints, 0: none).
import os

configfile: os.path.join(workflow.basedir, "config", "pack3d.yaml")

include: "rules/common.smk"

POINT = f"{RESULTS}/points/{{setup}}_R{{R}}_seed{{seed}}.json"
OUT = f"{RESULTS}/phi_max"
# numbers also when given as --config R=[...] (which gives strings)
POINTS = expand(POINT, setup=config["setups"], R=[fmt(R) for R in config["R"]],
                seed=[int(s) for s in config["seeds"]])

localrules: all, phi_max

wildcard_constraints:
    setup="[a-z_]+",
    R="[0-9.]+",
    seed="[0-9]+",


rule all:
    input:
        POINTS,  # a deleted point runs again, then the table and plot
        f"{OUT}.csv",
        f"{OUT}.png",
        f"{OUT}_fit.csv",


rule point:
    output:
        POINT,
    params:
        variables=lambda w: {"R": w.R, "seed": w.seed, "output": False,
                             "checkpoint_every": config["checkpoint_every"], **config["vars"]},
    threads: config["threads"]
    resources:
        **POINT_RESOURCES,
    run:
        sweep.run_point(RUNNER, output[0], os.path.join(REPO, "examples", "pack3d", wildcards.setup + ".lua"),
                        params.variables, f"{RESULTS}/work/{wildcards.setup}_R{wildcards.R}_seed{wildcards.seed}",
                        threads=threads)


rule phi_max:
    input:
        POINTS,
    output:
        f"{OUT}.csv",
        f"{OUT}.png",
        f"{OUT}_fit.csv",
    run:
        studies.phi_max_outputs(sweep.load_records(input), OUT)
