#!/usr/bin/python3
"""grainflow.resumable (python/grainflow) against a stand-in for `grainflow run` (below): a piece that ends by
itself, one stopped by its budget and continued from its checkpoint, one stopped early by a test on
its series, a row still being written left out of the series, and the archive's compressed
checkpoint restored byte for byte (older archives' plain checkpoints too)."""
import gzip
import json
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

import grainflow.resumable as r  # the package under python/, on PYTHONPATH

# The stand-in: a series row (time = row / 10) every 10 ms up to --set rows=N; SIGINT stops it
# after the row in flight. Its checkpoint holds the rows done, from which --resume continues; the
# summary has the keys run_piece reads.
FAKE = r'''
import signal
stop = []
signal.signal(signal.SIGINT, lambda *_: stop.append(1))  # first, so no SIGINT finds it without
import json, sys, time
from pathlib import Path
a = sys.argv
out = Path(a[a.index("--out") + 1])
rows = int([v for k, v in zip(a, a[1:]) if k == "--set" and v.startswith("rows=")][0][5:])
start = int(Path(a[a.index("--resume") + 1]).read_text()) if "--resume" in a else 0
out.mkdir(parents=True, exist_ok=True)
series = out / "series.csv"
if start == 0:
    series.write_text("time,angle\n")
k, t0 = start, time.time()
while k < rows and not stop:
    k += 1
    with open(series, "a") as f:
        f.write(f"{k / 10},{k / 10}\n")
    time.sleep(0.01)
(out / "checkpoints").mkdir(exist_ok=True)
(out / "checkpoints" / "checkpoint.gfc").write_text(str(k))
(out / "summary.json").write_text(json.dumps({"status": "interrupted" if stop else "completed", "steps": k,
    "steps_this_run": k - start, "wall_seconds": time.time() - t0, "particle_steps_per_second": None}))
'''

failures = []


def check(name, ok, detail=""):
    if not ok:
        failures.append(f"{name}: {detail}")


def last_time(folder):
    return float(r.load_series(folder)["time"][-1])


def never_done(series):
    return False


work = Path(tempfile.mkdtemp(prefix="resumable_test_"))
try:
    binary = work / "fake_grainflow"
    binary.write_text("#!" + sys.executable + "\n" + FAKE)
    binary.chmod(0o755)
    scene = work / "scene.toml"
    scene.write_text("")

    # Ends by itself well inside its budget: no SIGINT, all 20 rows.
    own = work / "own"
    piece = r.run_piece("own", binary, scene, own, ["rows=20"], 1, 30.0, never_done)
    check("own end: status", piece["status"] == "completed" and piece["stopped_by"] is None, piece)
    check("own end: rows", last_time(own) == 2.0, last_time(own))

    # Out of budget after 3 s of about 200 s of rows: interrupted with its checkpoint, and the next
    # piece resumes from it (the stand-in counts on from the checkpoint's rows, so the series runs
    # on with no row missing or repeated).
    budget = work / "budget"
    piece = r.run_piece("budget", binary, scene, budget, ["rows=20000"], 1, 3.0, never_done)
    check("budget: stopped", piece["status"] == "interrupted" and piece["stopped_by"] == "budget", piece)
    first = piece["steps_total"]
    piece = r.run_piece("budget", binary, scene, budget, ["rows=20000"], 1, 3.0, never_done)
    times = list(r.load_series(budget)["time"])
    check("budget: resumed", piece["steps_total"] > first and times == [k / 10 for k in range(1, len(times) + 1)],
          (first, piece["steps_total"], times[:3], times[-3:]))
    check("budget: two pieces logged", len(r.pieces(budget)) == 2, r.pieces(budget))

    # A stop test that holds once the series reaches 1 s, read every 0.05 s: the piece ends then,
    # not at its 60 s budget (each row takes about 10 ms, so the stop lands within a few tenths of a
    # second; the bounds leave room for a loaded machine).
    early = work / "early"
    t0 = time.time()
    piece = r.run_piece("early", binary, scene, early, ["rows=20000"], 1, 60.0, never_done,
                        stop=lambda s: float(s["time"][-1]) >= 1.0, poll_s=0.05)
    check("stop test: stopped", piece["stopped_by"] == "stop test" and piece["status"] == "interrupted", piece)
    check("stop test: soon after the condition", 1.0 <= last_time(early) < 100.0 and time.time() - t0 < 30.0,
          (last_time(early), time.time() - t0))

    # A stop test that never holds does not end a piece that ends by itself.
    late = work / "late"
    piece = r.run_piece("late", binary, scene, late, ["rows=15"], 1, 30.0, never_done,
                        stop=lambda s: False, poll_s=0.05)
    check("stop test never holding", piece["stopped_by"] is None and last_time(late) == 1.5, piece)

    # A row still being written (no newline yet) is not part of the series.
    (early / "series.csv").open("a").write("99.")
    check("partial row left out", last_time(early) < 99.0, last_time(early))

    # The archive keeps the checkpoint gzip-compressed, the same bytes for the same checkpoint, and
    # restore unpacks it byte for byte; a finished case drops it.
    ckpt = budget / "checkpoints" / "checkpoint.gfc"
    ckpt.write_bytes(os.urandom(1000) + bytes(200000))
    dest = work / "archive" / "budget"
    r.archive(budget, dest, False)
    packed = dest / "checkpoints" / "checkpoint.gfc.gz"
    check("archive: compressed", packed.is_file() and not (dest / "checkpoints" / "checkpoint.gfc").exists())
    check("archive: smaller", packed.stat().st_size < ckpt.stat().st_size / 10, packed.stat().st_size)
    check("archive: gzip of the checkpoint", gzip.decompress(packed.read_bytes()) == ckpt.read_bytes())
    before = packed.read_bytes()
    r.archive(budget, dest, False)
    check("archive: same bytes again", packed.read_bytes() == before)
    back = work / "restored"
    r.restore(back, dest)
    check("restore: checkpoint byte for byte", (back / "checkpoints" / "checkpoint.gfc").read_bytes() == ckpt.read_bytes())
    check("restore: no packed copy left", not (back / "checkpoints" / "checkpoint.gfc.gz").exists())
    check("restore: series", last_time(back) == last_time(budget))

    # An archive written before compression (a plain checkpoint) restores as it is, and archiving
    # into it replaces the plain copy by the compressed one.
    old = work / "archive" / "old"
    shutil.copytree(dest, old)
    (old / "checkpoints" / "checkpoint.gfc.gz").unlink()
    shutil.copy2(ckpt, old / "checkpoints" / "checkpoint.gfc")
    r.restore(work / "from_old", old)
    check("restore of a plain archive", (work / "from_old" / "checkpoints" / "checkpoint.gfc").read_bytes() == ckpt.read_bytes())
    r.archive(budget, old, False)
    check("plain archive replaced", sorted(p.name for p in (old / "checkpoints").iterdir()) == ["checkpoint.gfc.gz"],
          list((old / "checkpoints").iterdir()))
    r.archive(budget, dest, True)
    check("finished: checkpoint dropped", not (dest / "checkpoints").exists())
    check("finished: summary kept", json.loads((dest / "summary.json").read_text())["steps"] > 0)
finally:
    shutil.rmtree(work, ignore_errors=True)

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("resumable: all checks pass")
