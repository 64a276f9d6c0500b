"""What the study scripts that are entry points over a Snakemake workflow share
(scripts/phase_diagram.py, pack3d_sweep.py, dt_ladder.py): the workflow's command line
from the script's options, run in the repository, and the copy of its outputs."""
import os
import shlex
import shutil
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def add_options(ap, default_cores):
    """The options every entry point takes besides its own study's."""
    ap.add_argument("--cores", type=int, default=default_cores)
    ap.add_argument("--profile", default="local", choices=["local", "slurm"])
    ap.add_argument("--dry-run", action="store_true", help="print what would run and exit")


def yaml_list(values):
    """A --config list: numbers as %g, strings as YAML strings."""
    def item(x):
        if isinstance(x, float):
            return f"{x:g}"
        if isinstance(x, str):
            return "'" + x.replace("'", "''") + "'"
        return str(x)
    return "[" + ", ".join(item(x) for x in values) + "]"


def yaml_vars(pairs):
    """A --config map of NAME=VALUE strings (values as YAML reads them)."""
    return "{" + ", ".join(f"{k}: {v}" for k, v in (p.split("=", 1) for p in pairs)) + "}"


def run(workflow, config, a):
    """Runs workflows/<workflow>.smk with its config file and these --config entries on
    a.cores cores with a.profile (a dry run with a.dry_run); returns its exit status."""
    cmd = ["snakemake", "-s", os.path.join(ROOT, "workflows", workflow + ".smk"),
           "--profile", os.path.join(ROOT, "workflows", "profiles", a.profile),
           "--configfile", os.path.join(ROOT, "workflows", "config", workflow + ".yaml"),
           "--directory", ROOT, "--cores", str(a.cores), "--config", *config]
    if a.dry_run:
        cmd += ["--dry-run", "--quiet"]
    print(" ".join(shlex.quote(c) for c in cmd), flush=True)
    return subprocess.run(cmd).returncode


def copy_outputs(made, out, suffixes):
    """Copies made + suffix to out + suffix for each suffix that exists."""
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    for suffix in suffixes:
        if os.path.exists(made + suffix):
            shutil.copyfile(made + suffix, out + suffix)
