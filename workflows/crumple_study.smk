# How a 2D crumpling deck's final wire depends on one of its choices
# (scripts/crumple_study.py as a workflow): every (value, seed) of the config runs
# examples/crumple2d/<deck>.lua with -v <variable>=<value> to max_phi or its jam, one job
# each, with a checkpoint every checkpoint_every steps, so a long run (f = 100 takes an
# hour) that a sitting or a Slurm limit cuts short continues on the next call. The table,
# its Markdown and the picture of the final wires are those of the script.
#
#   snakemake -s workflows/crumple_study.smk --profile workflows/profiles/local \
#       --config variable=drag_factor 'values=[1, 0.1]' f=50 'seeds=[1, 2, 3]'
#
# Config (workflows/config/crumple_study.yaml, and rules/common.smk): deck, f, variable,
# label (its name in the table; default the variable), values, seeds, max_phi (1: to the
# jam), set (further -v variables of every run, e.g. {damping: relative}),
# checkpoint_every, retry_unstable.
import os

configfile: os.path.join(workflow.basedir, "config", "crumple_study.yaml")

include: "rules/common.smk"

DECK = os.path.join(REPO, "examples", "crumple2d", config["deck"] + ".lua")
VARIABLE = config["variable"]
LABEL = config.get("label") or VARIABLE
F = float(config["f"])
VALUES = list(config["values"])
VALUE_TEXT = [str(v) for v in VALUES]
SEEDS = [int(s) for s in config["seeds"]]
POINT = f"{RESULTS}/points/v{{value}}_seed{{seed}}"
STOP = "to the jam" if float(config["max_phi"]) >= 1 else f"to phi = {float(config['max_phi']):g}"
FIXED = ", ".join(f"{k}={v}" for k, v in config["set"].items())
TITLE = f"{config['deck']}, f = {F:g}{f' ({FIXED})' if FIXED else ''}, {STOP}: the wire against {LABEL}"
OUT = f"{RESULTS}/{config['deck']}_f{fmt(F)}_{VARIABLE}"

localrules: all, study

wildcard_constraints:
    value="[A-Za-z0-9._+-]+",  # deck values such as by_speed; the suffix _seed<n> anchors the match
    seed="[0-9]+",


rule all:
    input:
        expand(POINT + ".json", value=VALUE_TEXT, seed=SEEDS),
        f"{OUT}.csv",
        f"{OUT}.md",
        f"{OUT}.png",


rule point:
    output:
        json=POINT + ".json",
        wire=POINT + ".npy",
    params:
        variables=lambda w: {"f": config["f"], VARIABLE: w.value, "seed": w.seed,
                             "max_phi": config["max_phi"], "output": False,
                             # the checkpoint dump also writes the state the run stops in:
                             # the final wire that the shape measures and the picture read
                             "checkpoint_every": config["checkpoint_every"] or 10 ** 12,
                             **config["set"], **config["vars"]},
    threads: config["threads"]
    resources:
        **POINT_RESOURCES,
    run:
        sweep.run_point(RUNNER, output.json, DECK, params.variables,
                        f"{RESULTS}/work/v{wildcards.value}_seed{wildcards.seed}",
                        threads=threads, retry=config["retry_unstable"],
                        measure=lambda folder: studies.crumple_measures(folder, F, output.wire),
                        extra={"study_variable": VARIABLE})
        if not os.path.exists(output.wire):
            open(output.wire, "w").close()  # no final state: the picture leaves it out


rule study:
    input:
        json=expand(POINT + ".json", value=VALUE_TEXT, seed=SEEDS),
        wire=expand(POINT + ".npy", value=VALUE_TEXT, seed=SEEDS),
    output:
        f"{OUT}.csv",
        f"{OUT}.md",
        f"{OUT}.png",
    run:
        studies.crumple_study_outputs(sweep.load_records(input.json), input.wire, OUT, TITLE, LABEL,
                                      VALUES, SEEDS)
