# The 2D crumpling phase diagram (scripts/phase_diagram.py as a workflow): every
# (yield curvature, static friction, seed) of the config's grid runs
# examples/crumple2d/<deck>.lua to its jam, one job each; the table and the plots are
# those of the script (its classify and draw, through lib/studies.py).
#
#   snakemake -s workflows/phase_diagram.smk --profile workflows/profiles/local
#
# Config (workflows/config/phase_diagram.yaml, and rules/common.smk): f, s, yields,
# mus, seeds, deck; checkpoint_every (steps between a run's checkpoints, 0: none);
# retry_unstable (-v variables of a second run when the instability guard stops the
# first, null: no second run).
import os

configfile: os.path.join(workflow.basedir, "config", "phase_diagram.yaml")

include: "rules/common.smk"

DECK = os.path.join(REPO, "examples", "crumple2d", config["deck"] + ".lua")
POINT = f"{RESULTS}/points/y{{y}}_mu{{mu}}_seed{{seed}}.json"
OUT = f"{RESULTS}/phase_diagram_f{fmt(config['f'])}"
# numbers also when given as --config yields=[...] (which gives strings)
YIELDS = sorted(float(y) for y in config["yields"])
MUS = sorted(float(mu) for mu in config["mus"])
POINTS = expand(POINT, y=[fmt(y) for y in YIELDS], mu=[fmt(mu) for mu in MUS],
                seed=[int(s) for s in config["seeds"]])

localrules: all, diagram

wildcard_constraints:
    y="[0-9.e+-]+",
    mu="[0-9.e+-]+",
    seed="[0-9]+",


rule all:
    input:
        POINTS,  # a deleted point runs again, then the table and plots
        f"{OUT}.csv",
        f"{OUT}.png",
        f"{OUT}_phi.png",
        f"{OUT}_thumbnails.png",


rule point:
    output:
        POINT,
    params:
        variables=lambda w: {"f": config["f"], "s": config["s"], "yield": w.y, "mu": w.mu,
                             "seed": w.seed, "output": False,
                             # the checkpoint dump also writes the state the run stops in:
                             # the point's thumbnail
                             "checkpoint_every": config["checkpoint_every"] or 10 ** 12,
                             **config["vars"]},
    threads: config["threads"]
    resources:
        **POINT_RESOURCES,
    run:
        sweep.run_point(RUNNER, output[0], DECK, params.variables,
                        f"{RESULTS}/work/y{wildcards.y}_mu{wildcards.mu}_seed{wildcards.seed}",
                        threads=threads, retry=config["retry_unstable"],
                        thumbnail=(output[0][:-len(".json")] + ".png", float(config["f"])))


rule diagram:
    input:
        POINTS,
    output:
        f"{OUT}.csv",
        f"{OUT}.png",
        f"{OUT}_phi.png",
        f"{OUT}_thumbnails.png",
    run:
        studies.phase_diagram_outputs(sweep.load_records(input), OUT, YIELDS, MUS, float(config["f"]),
                                      thumbnails=os.path.dirname(POINT))
