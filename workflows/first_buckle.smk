# Where the straight 2D wire first buckles, against the feed speed (scripts/first_buckle.py
# as a workflow): every (f, speed) of the config runs examples/crumple2d/<deck>.lua from its
# straight start until `feed` cavity radii of wire have entered per channel, one job each,
# and measures the buckled wire (peak position, half-waves, central share, the span number
# Pi). The table and the picture of the wires are those of the script.
#
#   snakemake -s workflows/first_buckle.smk --profile workflows/profiles/local \
#       --config 'f=[50, 100]' 'speeds=[0.08, 0.02]'
#
# Config (workflows/config/first_buckle.yaml, and rules/common.smk): deck, f (cavity
# radii), speeds, feed, seed, checkpoint_every.
import os

configfile: os.path.join(workflow.basedir, "config", "first_buckle.yaml")

include: "rules/common.smk"

DECK = os.path.join(REPO, "examples", "crumple2d", config["deck"] + ".lua")
FS = [fmt(f) for f in config["f"]]
SPEEDS = [fmt(v) for v in config["speeds"]]
FEED = float(config["feed"])
SEED = int(config["seed"])
POINT = f"{RESULTS}/points/f{{f}}_v{{speed}}"
OUT = f"{RESULTS}/first_buckle"

localrules: all, table

wildcard_constraints:
    f="[0-9.e+-]+",
    speed="[0-9.e+-]+",


rule all:
    input:
        f"{OUT}.csv",
        f"{OUT}.png",


rule point:
    output:
        json=POINT + ".json",
        wire=POINT + ".npy",
    params:
        variables=lambda w: {**studies.first_buckle.point_variables(float(w.f), float(w.speed), FEED, SEED),
                             "output": False,
                             # the checkpoint dump also writes the state the run stops in
                             "checkpoint_every": config["checkpoint_every"] or 10 ** 12,
                             **config["vars"]},
    threads: config["threads"]
    resources:
        **POINT_RESOURCES,
    run:
        sweep.run_point(RUNNER, output.json, DECK, params.variables,
                        f"{RESULTS}/work/f{wildcards.f}_v{wildcards.speed}", threads=threads,
                        measure=lambda folder: studies.first_buckle_measures(folder, float(wildcards.f),
                                                                              output.wire))
        if not os.path.exists(output.wire):
            open(output.wire, "w").close()  # no final state: the picture leaves it out


rule table:
    input:
        json=expand(POINT + ".json", f=FS, speed=SPEEDS),
        wire=expand(POINT + ".npy", f=FS, speed=SPEEDS),
    output:
        f"{OUT}.csv",
        f"{OUT}.png",
    run:
        studies.first_buckle_outputs(sweep.load_records(input.json), input.wire, OUT, config["deck"], FEED)
