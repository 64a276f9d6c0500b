# Shared by the study workflows (workflows/*.smk): where the repository, the binary and
# the results are, and the DeckRunner every point rule runs its deck with.
#
# Config keys of every study (workflows/config/*.yaml; any can be overridden with
# --config key=value):
#   slender           the binary (default: <repo>/build/slender)
#   results           folder of the per-point JSON records, the tables and the plots
#   threads           threads per deck run (slender -t)
#   timeout           seconds per deck run (null: none)
#   runtime, mem_mb   per deck run, in minutes and MiB: the Slurm allocation
#   vars              further -v variables for every run
import os
import sys

REPO = os.path.dirname(workflow.basedir)
sys.path.insert(0, os.path.join(workflow.basedir, "lib"))

import studies
import sweep

config.setdefault("slender", os.path.join(REPO, "build", "slender"))
config.setdefault("threads", 1)
config.setdefault("runtime", 60)
config.setdefault("mem_mb", 1000)
config.setdefault("timeout", None)
config.setdefault("vars", {})
RESULTS = config["results"]
RUNNER = sweep.DeckRunner(os.path.abspath(config["slender"]), os.path.join(REPO, "python"),
                          timeout=config["timeout"])


def fmt(value):
    """A grid number as it appears in file names and -v variables (0.05, 4)."""
    return f"{float(value):g}"


# the Slurm allocation of one deck run (cpus_per_task: the profile's default would
# otherwise replace the rule's threads)
POINT_RESOURCES = dict(runtime=config["runtime"], mem_mb=config["mem_mb"],
                       cpus_per_task=lambda wildcards, threads: threads)
