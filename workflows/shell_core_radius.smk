# The e-cone's core radius against the thickness h, on meshes whose core is refined more
# and more (scripts/shell_core_radius.py as a workflow; docs/models.md §6.11, §7.2 S-1):
# every (h, level) runs examples/shells/econe.lua without self-contact up to phi_e, one
# job each writing one record; the table rule writes the script's CSV (one row per run)
# and its picture (R_C(h) per level with a power-law fit on the finest level, and R_C
# against the core edge).
#
#   snakemake -s workflows/shell_core_radius.smk --profile workflows/profiles/local
#   snakemake -s workflows/shell_core_radius.smk --profile workflows/profiles/local \
#       --config 'h=[0.04, 0.02, 0.01]' 'levels=[2, 3]'
#
# Config (workflows/config/shell_core_radius.yaml, and rules/common.smk): h (thicknesses
# over the disc radius), levels (refinement levels of the core, refine_center = 0.3),
# edge (the disc's outer edge), phi (the end of the ramp, below the first contact of
# every h), name (of the table and picture).
import json
import os
import sys
from types import SimpleNamespace

configfile: os.path.join(workflow.basedir, "config", "shell_core_radius.yaml")

include: "rules/common.smk"

sys.path.insert(0, os.path.join(REPO, "scripts"))
import shell_core_radius as scr

HS = [fmt(h) for h in config["h"]]
LEVELS = [int(v) for v in config["levels"]]
POINT = f"{RESULTS}/points/h{{h}}_level{{level}}.json"
OUT = f"{RESULTS}/{config['name']}"

localrules: all, table

wildcard_constraints:
    h="[0-9.e+-]+",
    level="[0-9]+",


rule all:
    input:
        expand(POINT, h=HS, level=LEVELS),
        f"{OUT}.csv",
        f"{OUT}.png",


rule point:
    output:
        POINT,
    resources:
        **POINT_RESOURCES,
    run:
        study = SimpleNamespace(slender=os.path.abspath(config["slender"]),
                                examples=os.path.join(REPO, "examples"),
                                edge=float(config["edge"]), phi=float(config["phi"]))
        row = scr.run_one(study, float(wildcards.h), int(wildcards.level))
        with open(output[0], "w") as fh:
            json.dump(row, fh, indent=1)


rule table:
    input:
        expand(POINT, h=HS, level=LEVELS),
    output:
        csv=f"{OUT}.csv",
        png=f"{OUT}.png",
    run:
        import csv
        rows = [{k: str(v) for k, v in json.load(open(f)).items()} for f in input]
        with open(output.csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, scr.FIELDS, extrasaction="ignore")
            w.writeheader()
            w.writerows(rows)
        scr.plot(rows, OUT)
        if not os.path.exists(output.png):  # no run succeeded: an empty picture says so
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
            fig = plt.figure(figsize=(4, 1))
            fig.text(0.1, 0.5, "no successful run")
            fig.savefig(output.png)
