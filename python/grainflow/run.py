"""Running `grainflow run` from Python and reading what it wrote.

    from grainflow.run import run_scene
    run = run_scene("scenes/drum_quick.toml", "runs/drum_quick", sets=["run.dt=2e-5"], steps=1000)
    run.series["lacey_index"][-1]

The binary is `binary` when given, else $GRAINFLOW_BINARY, else build/grainflow of the repository
this package lies in.
"""
import os
import subprocess
from pathlib import Path

from grainflow.outputs import Run

REPO = Path(__file__).resolve().parents[2]  # python/grainflow/run.py


class RunError(RuntimeError):
    """`grainflow run` exited with a non-zero status; `returncode` and `stderr` say how."""

    def __init__(self, message, returncode, stderr):
        super().__init__(message)
        self.returncode = returncode
        self.stderr = stderr


def default_binary():
    """$GRAINFLOW_BINARY when set, else <repository>/build/grainflow."""
    env = os.environ.get("GRAINFLOW_BINARY")
    return Path(env) if env else REPO / "build" / "grainflow"


def command(scene, out, sets=(), steps=None, threads=None, binary=None, resume=None, quiet=True, overwrite=False):
    """The command line run_scene runs, as a list."""
    if isinstance(sets, str):
        sets = [sets]
    elif isinstance(sets, dict):
        sets = [f"{k}={v}" for k, v in sets.items()]
    cmd = [str(binary if binary is not None else default_binary()), "run", str(scene), "--out", str(out)]
    for s in sets:
        cmd += ["--set", str(s)]
    if steps is not None:
        cmd += ["--steps", str(int(steps))]
    if threads is not None:
        cmd += ["--threads", str(int(threads))]
    if resume is not None:
        cmd += ["--resume", str(resume)]
    if overwrite:
        cmd.append("--overwrite")
    if quiet:
        cmd.append("--quiet")
    return cmd


def run_scene(scene, out, sets=(), steps=None, threads=None, binary=None, check=True, resume=None, quiet=True,
              overwrite=False):
    """Runs `grainflow run SCENE --out OUT [--set ...] [--steps N] [--threads N]`, waits for it and
    returns the Run of OUT. `sets` is a list of "key=value" overrides (or a dict of them). With check,
    a non-zero exit raises RunError carrying the program's stderr; without it the Run is returned
    whatever the status (its summary says how the run ended), or RunError when no folder was written.
    grainflow refuses a folder that holds an earlier run unless `overwrite` (which clears it) or `resume`."""
    exe = Path(binary) if binary is not None else default_binary()
    if not exe.is_file():
        raise FileNotFoundError(f"{exe}: no grainflow binary (build it, or pass binary= or set $GRAINFLOW_BINARY)")
    cmd = command(scene, out, sets, steps, threads, exe, resume, quiet, overwrite)
    p = subprocess.run(cmd, capture_output=True, text=True)
    refused = p.returncode in (1, 2)  # bad input or command line: nothing ran, a folder there is older
    if p.returncode != 0 and (check or refused or not Path(out).is_dir()):
        raise RunError(f"{' '.join(cmd)} exited with status {p.returncode}:\n{p.stderr.strip()}",
                       p.returncode, p.stderr)
    return Run(out)
