# The example suite (scripts/run-examples as a workflow; by default its full mode, the
# decks' own parameters, hours in all): one job per deck, in its own folder under
# <results>/decks/ where its plots stay, and a summary table (<results>/summary.md,
# <results>/examples.csv) with each deck's status, wall time and headline numbers. A
# failing deck is recorded, not retried (delete its JSON, or --forcerun, to run it again).
#
#   snakemake -s workflows/examples.smk --profile workflows/profiles/local
#
# Config (workflows/config/examples.yaml, and rules/common.smk): fast (true: -v fast=1,
# the suite's fast mode), decks (patterns of run-examples' PATTERN; empty: every deck),
# checkpoint_every (steps between the checkpoints of the decks that can resume; 0: none,
# a cut-short run still leaves its state).
import os

configfile: os.path.join(workflow.basedir, "config", "examples.yaml")

include: "rules/common.smk"

EXAMPLES = os.path.join(REPO, "examples")
DECKS = studies.find_decks(EXAMPLES, config["decks"])
MODE = "fast" if config["fast"] else "full"
RECORD = f"{RESULTS}/decks/{{deck}}.json"
RECORDS = expand(RECORD, deck=DECKS)

localrules: all, summary

wildcard_constraints:
    deck="[A-Za-z0-9_/]+",


rule all:
    input:
        RECORDS,  # a deleted deck record runs again, then the summary
        f"{RESULTS}/summary.md",
        f"{RESULTS}/examples.csv",


def deck_path(deck):
    return os.path.join(EXAMPLES, deck + ".lua")


def deck_variables(wildcards):
    """The -v variables of one deck: fast mode, and for a deck that can continue from a
    checkpoint (-v restart=, studies.resumable) the checkpoint cadence."""
    variables = {"fast": 1} if config["fast"] else {}
    if config["checkpoint_every"] and studies.resumable(deck_path(wildcards.deck)):
        variables["checkpoint_every"] = config["checkpoint_every"]
    return {**variables, **config["vars"]}


rule deck:
    output:
        RECORD,
    params:
        variables=deck_variables,
    threads: config["threads"]
    resources:
        **POINT_RESOURCES,
    run:
        # a deck that reads -v restart= continues from the state its cut-short run left
        # (a timeout, SIGTERM from Slurm or Ctrl-C); the others start again
        deck = deck_path(wildcards.deck)
        sweep.run_point(RUNNER, output[0], deck, params.variables, f"{RESULTS}/decks/{wildcards.deck}",
                        threads=threads, resume=studies.resumable(deck), keep_work=True,
                        record_failures=True)


rule summary:
    input:
        RECORDS,
    output:
        f"{RESULTS}/summary.md",
        f"{RESULTS}/examples.csv",
    run:
        studies.examples_outputs(DECKS, sweep.load_records(input), RESULTS, MODE)
