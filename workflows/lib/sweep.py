"""Helpers of the study workflows (workflows/*.smk): each job runs one deck through
`python3 -m slender run` in a work folder that outlives the job, so a run cut short (a
Slurm time limit, a timeout, a lost node) continues from its checkpoint when Snakemake
runs the same job again."""
import csv
import glob
import json
import os
import shutil
import subprocess
import sys

RUN_JSON = "run.json"  # the runner's record of the latest run, in the work folder
VARIABLES_JSON = "variables.json"  # the variables the work folder's checkpoints belong to


def lua_value(value):
    """The -v text of a config value; YAML's booleans as Lua writes them."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def newest_checkpoint(work):
    """The newest state a cut-short run left in work: the deck's checkpoint dump
    (<name>_restart.h5, where SIGTERM writes too) or, for a deck without one, the
    slender_interrupted.h5 that SIGTERM writes."""
    found = glob.glob(os.path.join(work, "*_restart.h5"))
    found += glob.glob(os.path.join(work, "slender_interrupted.h5"))
    return max(found, key=os.path.getmtime) if found else None


def unstable(record):
    """Stopped by the instability guard after reporting its last good state (the
    crumpling decks print ended=instability before exiting 3)."""
    return record["status"] != "ok" and record["result"].get("ended") == "instability"


def settled(record):
    """Ended by itself: running it again would give the same record."""
    return record["status"] == "ok" or unstable(record)


class DeckRunner:
    """How every job of a workflow runs its deck: the binary, the repository's Python
    package and a timeout in seconds (None: none)."""

    def __init__(self, slender, python_dir, timeout=None):
        self.slender, self.python_dir, self.timeout = slender, python_dir, timeout

    def run(self, deck, variables, work, resume, threads=1):
        """One run of deck in work; returns the runner's JSON record, with resumed_from
        naming the checkpoint it continued (resume: from an earlier run of the same
        variables in work), else None."""
        variables = {k: lua_value(v) for k, v in variables.items()}
        checkpoint = self.checkpoint_of(variables, work) if resume else None
        os.makedirs(work, exist_ok=True)
        args = dict(variables)
        if checkpoint:
            args["restart"] = os.path.basename(checkpoint)
        cmd = [sys.executable, "-m", "slender", "run", os.path.abspath(deck), "-t", str(threads),
               "--keep", os.path.abspath(work), "--json", RUN_JSON]
        if self.timeout:
            cmd += ["--timeout", str(self.timeout)]
        for name, value in args.items():
            cmd += ["-v", f"{name}={value}"]
        path = os.path.join(work, RUN_JSON)
        if os.path.exists(path):
            os.remove(path)
        env = dict(os.environ, SLENDER_BIN=self.slender,
                   PYTHONPATH=os.pathsep.join(filter(None, [self.python_dir, os.environ.get("PYTHONPATH")])))
        # exits nonzero unless the run's status is ok: the record says why
        subprocess.run(cmd, cwd=work, env=env, check=False)
        if not os.path.exists(path):
            raise RuntimeError(f"{' '.join(cmd)} (in {work}) wrote no {RUN_JSON}")
        with open(path) as fh:
            record = json.load(fh)
        record["resumed_from"] = os.path.basename(checkpoint) if checkpoint else None
        return record

    @staticmethod
    def checkpoint_of(variables, work):
        """The checkpoint to continue in work, if an earlier run of these variables left
        one; a folder of other variables (the config changed) is emptied first."""
        path = os.path.join(work, VARIABLES_JSON)
        if os.path.exists(path):
            with open(path) as fh:
                if json.load(fh) == variables:
                    return newest_checkpoint(work)
            shutil.rmtree(work)
        os.makedirs(work, exist_ok=True)
        with open(path, "w") as fh:
            json.dump(variables, fh)
        return None


def draw_thumbnail(runner, work, png, radius):
    """png: the final state the run in work left (its checkpoint dump, written when the run
    stopped), drawn small with slender.plot.thumbnail; False if there is none."""
    checkpoint = newest_checkpoint(work)
    if not checkpoint:
        return False
    if runner.python_dir not in sys.path:
        sys.path.insert(0, runner.python_dir)
    from slender import plot
    plot.thumbnail(checkpoint, png, radius=radius)
    return True


def run_point(runner, output, deck, variables, work, threads=1, retry=None, resume=True,
              keep_work=False, record_failures=False, thumbnail=None, measure=None, extra=None):
    """Runs one point of a study and writes its record to output.

    retry: variables replacing some of `variables` for a second run (in work/retry) when
    the instability guard stops the first. resume: continue from a checkpoint left in
    work by an earlier job (the decks' -v restart=FILE). A run that did not end by itself
    raises (the job fails and keeps its work folder, so a rerun continues it) unless
    record_failures (then a run cut short still raises when it can resume). work
    is removed on success unless keep_work (the example decks' plots; then its
    checkpoints are removed, so that a forced rerun starts afresh). thumbnail = (png, radius): a small picture of the final state, from the
    checkpoint the deck wrote when it stopped (2D decks). measure(folder): a dict of
    measures of the final state in the run's work folder, kept as record["measures"].
    extra: further keys of the record."""
    record = runner.run(deck, variables, work, resume, threads)
    if retry and unstable(record):
        first = record
        record = runner.run(deck, {**variables, **retry}, os.path.join(work, "retry"), resume, threads)
        record["retried_with"], record["first_error"] = retry, first["error"]
    # a run cut short (the timeout, or a signal: exit code 130) that can continue from its
    # checkpoint is never recorded as failed: the job fails, and the next call continues it
    cut_short = resume and (record["status"] == "timeout" or record["returncode"] == 130)
    if not (settled(record) or (record_failures and not cut_short)):
        raise RuntimeError(f"{deck} {variables}: {record['status']}: {record['error']} "
                           f"(its state stays in {work} for the next attempt)")
    os.makedirs(os.path.dirname(os.path.abspath(output)), exist_ok=True)
    folder = os.path.join(work, "retry") if "retried_with" in record else work
    if measure:
        record["measures"] = measure(folder)
    record.update(extra or {})
    if thumbnail:
        record["thumbnail"] = os.path.basename(thumbnail[0]) if draw_thumbnail(
            runner, folder, thumbnail[0], thumbnail[1]) else None
    with open(output, "w") as fh:
        json.dump(record, fh, indent=1)
    if keep_work:
        # a forced rerun must start afresh: neither the record nor a state to continue
        os.remove(os.path.join(work, RUN_JSON))
        while newest_checkpoint(work):
            os.remove(newest_checkpoint(work))
    else:
        shutil.rmtree(work)


def load_records(paths):
    records = []
    for path in paths:
        with open(path) as fh:
            records.append(json.load(fh))
    return records


def write_table(path, fields, rows):
    with open(path, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fields, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
