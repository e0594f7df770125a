"""One long grainflow run in resumable pieces that survives a new checkout: after every piece its
results (and, while it is unfinished, its last checkpoint) are archived under a committed folder,
and a run folder that is missing is restored from there first (grainflow.resumable).

    PYTHONPATH=python /usr/bin/python3 -m grainflow.long_run SCENE --out runs/NAME --archive studies/STUDY/results/NAME \\
        [--set key=value ...] [--keep layers.csv residence.csv] [--budget-minutes 60] [--threads 1] \\
        [--binary build/grainflow]

Each call runs one piece of at most --budget-minutes (stopped with SIGINT, which writes the
checkpoint) unless summary.json says the run completed; call it again to go on. --keep names more
files of the run folder to archive beside series.csv, summary.json, pieces.jsonl and log.txt.
"""
import argparse
import json
import shutil
import sys
from pathlib import Path

from grainflow.resumable import archive, restore, run_piece

REPO = Path(__file__).resolve().parents[2]  # python/grainflow/long_run.py


def completed(folder):
    path = folder / "summary.json"
    return path.is_file() and json.loads(path.read_text()).get("status") == "completed"


def main():
    ap = argparse.ArgumentParser(prog="python3 -m grainflow.long_run", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", type=Path)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--archive", type=Path, required=True)
    ap.add_argument("--set", dest="overrides", action="append", default=[])
    ap.add_argument("--keep", nargs="*", default=[])
    ap.add_argument("--budget-minutes", type=float, default=60.0)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--binary", type=Path, default=REPO / "build" / "grainflow")
    a = ap.parse_args()
    if not a.binary.is_file():
        sys.exit(f"long_run: {a.binary} not found: build grainflow first (README)")
    restore(a.out, a.archive)
    for name in a.keep:  # the extra files come back too
        if (a.archive / name).is_file() and not (a.out / name).is_file():
            shutil.copy2(a.archive / name, a.out / name)
    run_piece(a.out.name, a.binary, a.scene, a.out, a.overrides, a.threads, 60 * a.budget_minutes,
              lambda series: completed(a.out))
    finished = completed(a.out)
    archive(a.out, a.archive, finished, extra=a.keep)
    print(f"{a.out.name}: {'completed' if finished else 'continues on the next call'}; archived in {a.archive}")


if __name__ == "__main__":
    main()
