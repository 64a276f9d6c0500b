"""Run slender decks and read their RESULT lines.

One place for what every study script did on its own: start the binary on a deck with
`-v name=value` overrides in a scratch folder, stop it at a timeout, and turn its
`RESULT key=value ...` lines (printed by `slender.result{...}`) into dictionaries.

Exit codes of the binary (src/main.cpp, src/lua_binding.cpp): 0 ok, 1 a deck error,
2 a usage error, 3 stopped by the instability guard, 130 stopped by SIGINT/SIGTERM
(after writing its last frame and checkpoint).
"""

import os
import re
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent.parent

STATUSES = ("ok", "failed", "timeout", "no-result")

# Seconds a run gets after SIGTERM to finish its step and write its last frame and
# checkpoint before it is killed.
TERMINATE_GRACE_S = 10.0

_INT = re.compile(r"[+-]?\d+")


def find_binary(binary=None):
    """The slender binary: `binary`, else $SLENDER_BIN, else build/slender in this
    repository, else `slender` on PATH. Raises FileNotFoundError when there is none."""
    for candidate in (binary, os.environ.get("SLENDER_BIN")):
        if candidate:
            return str(candidate)
    built = REPO / "build" / "slender"
    if built.is_file():
        return str(built)
    on_path = shutil.which("slender")
    if on_path:
        return on_path
    raise FileNotFoundError("no slender binary: set SLENDER_BIN, build build/slender, or put "
                            "slender on PATH")


def parse_value(text):
    """int or float when the text is one (as the deck printed it), else the text."""
    if _INT.fullmatch(text):
        return int(text)
    if "_" not in text:  # float() would read "1_0" as 10
        try:
            return float(text)
        except ValueError:
            pass
    return text


def parse_result_text(text):
    """One dict of verbatim strings per `RESULT k=v ...` line of text.

    slender.result prints string values as they are, so a value may hold spaces: a token
    without '=' continues the value before it."""
    results = []
    for line in text.splitlines():
        tokens = line.split()
        if not tokens or tokens[0] != "RESULT":
            continue
        rec, last = {}, None
        for tok in tokens[1:]:
            key, sep, value = tok.partition("=")
            if sep and key:
                rec[key], last = value, key
            elif last is not None:
                rec[last] += " " + tok
            else:
                rec["unparsed"] = (rec.get("unparsed", "") + " " + tok).strip()
        results.append(rec)
    return results


def parse_results(text):
    """One dict per RESULT line of text, values converted by parse_value."""
    return [{k: parse_value(v) for k, v in rec.items()} for rec in parse_result_text(text)]


def last_line(text):
    """The last non-empty line of text, stripped, or ''."""
    for line in reversed(text.splitlines()):
        if line.strip():
            return line.strip()
    return ""


def format_variables(variables):
    """{name: text} from a mapping, or from an iterable of "name=value" strings or
    (name, value) pairs; booleans as Lua writes them (true/false)."""
    if variables is None:
        return {}
    items = variables.items() if hasattr(variables, "items") else variables
    out = {}
    for item in items:
        if isinstance(item, str):
            name, sep, value = item.partition("=")
            if not sep or not name:
                raise ValueError(f"a deck variable needs name=value, got {item!r}")
        else:
            name, value = item
        if isinstance(value, bool):
            value = "true" if value else "false"
        out[str(name)] = str(value)
    return out


@dataclass
class RunResult:
    """What one run of a deck gave.

    status: "ok" (exit 0 and at least one RESULT line), "failed" (nonzero exit, or the
    binary could not start), "timeout", or "no-result" (exit 0 without a RESULT line).
    results: one dict per RESULT line (numbers converted); result: all of them merged,
    later lines winning; results_text: the same lines verbatim, for tables that must
    show exactly what the deck printed. error: the last line the run wrote to stderr
    (or stdout) when it did not succeed. wall_s: seconds the process ran, start-up
    included (a deck's own RESULT wall_s measures its physics only)."""
    deck: str
    command: list
    variables: dict
    status: str
    returncode: object
    wall_s: float
    results: list = field(default_factory=list)
    result: dict = field(default_factory=dict)
    results_text: list = field(default_factory=list)
    error: str = ""
    run_dir: object = None
    stdout: str = ""
    stderr: str = ""

    @property
    def ok(self):
        return self.status == "ok"

    def to_dict(self):
        """The JSON record of the run (without the console text)."""
        return {"deck": self.deck, "command": self.command, "variables": self.variables,
                "status": self.status, "returncode": self.returncode, "wall_s": self.wall_s,
                "result": self.result, "results": self.results, "error": self.error,
                "run_dir": self.run_dir}


def _stop(proc):
    """SIGTERM (the run finishes its step and writes its last frame and checkpoint), then
    SIGKILL if it has not ended within TERMINATE_GRACE_S; returns its output."""
    proc.terminate()
    try:
        return proc.communicate(timeout=TERMINATE_GRACE_S)
    except subprocess.TimeoutExpired:
        proc.kill()
        return proc.communicate()


def run_deck(deck, variables=None, threads=1, cwd=None, timeout=None, binary=None, keep=False,
             quiet=True, args=()):
    """Run `slender [-t threads] [-q] DECK -v name=value ...` and return a RunResult.

    The run works in `cwd` when given (created if missing, never removed); otherwise in
    a fresh temporary folder that is removed afterwards unless `keep` is true, so the
    outputs of many runs cannot overwrite each other. Relative paths in the deck's
    variables are relative to that folder. threads=None leaves the thread count to the
    binary (OMP_NUM_THREADS or 1). `args` are further options for the binary (e.g.
    ["--inventory", path]). At `timeout` seconds the run is stopped (see _stop) and
    its status is "timeout"."""
    deck = os.path.abspath(deck)
    values = format_variables(variables)
    command = [find_binary(binary)]
    if threads is not None:
        command += ["-t", str(threads)]
    if quiet:
        command.append("-q")
    command += [str(a) for a in args]
    command.append(deck)
    for name, value in values.items():
        command += ["-v", f"{name}={value}"]

    if cwd is not None:
        run_dir = os.path.abspath(cwd)
        os.makedirs(run_dir, exist_ok=True)
    else:
        run_dir = tempfile.mkdtemp(prefix="slender_run_")
    remove = cwd is None and not keep
    timed_out = False
    t0 = time.monotonic()
    try:
        try:
            proc = subprocess.Popen(command, cwd=run_dir, stdout=subprocess.PIPE,
                                    stderr=subprocess.PIPE, text=True, errors="replace")
        except OSError as exc:
            return RunResult(deck, command, values, "failed", None, time.monotonic() - t0,
                             error=f"cannot run {command[0]}: {exc}",
                             run_dir=None if remove else run_dir)
        try:
            out, err = proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
            out, err = _stop(proc)
        except BaseException:  # Ctrl-C or a signal in the caller: do not leave the run behind
            _stop(proc)
            raise
        wall = time.monotonic() - t0
    finally:
        if remove:
            shutil.rmtree(run_dir, ignore_errors=True)

    results_text = parse_result_text(out) or parse_result_text(err)
    results = [{k: parse_value(v) for k, v in rec.items()} for rec in results_text]
    merged = {}
    for rec in results:
        merged.update(rec)
    rc = proc.returncode
    if timed_out:
        status, error = "timeout", f"timeout after {timeout:g} s"
    elif rc != 0:
        status, error = "failed", last_line(err) or last_line(out) or f"exit status {rc}"
    elif not results:
        status = "no-result"
        error = "no RESULT line in the output" + (f": {last_line(err)}" if last_line(err) else "")
    else:
        status, error = "ok", ""
    return RunResult(deck, command, values, status, rc, wall, results, merged, results_text, error,
                     None if remove else run_dir, out, err)
