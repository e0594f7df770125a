"""One case of a study run in resumable pieces: the pieces, series and summary of its folder.

A piece runs `grainflow run SCENE --out FOLDER --set ...` (with --resume from the folder's last
checkpoint when there is one) for at most a wall-time budget, then stops it with SIGINT: grainflow
finishes the step in flight and writes its checkpoint, so the next piece continues where this one
stopped, bit-identical to an uninterrupted run. Every piece is logged in FOLDER/pieces.jsonl.
Used by studies/seed000/study.py, studies/seed001/kiln_map.py and grainflow.long_run.

A piece may also stop early on a condition of its series that the scene cannot state (a hopper
that has stopped draining): `stop(series)` is read every `poll_s` seconds while it runs, and once
it holds the piece gets SIGINT, so it ends with a checkpoint like a piece out of budget.

Run folders live under runs/, which git ignores, so a new checkout has none. `archive` copies a
case's results (and, while it is unfinished, its last checkpoint, gzip-compressed) into a committed
folder under studies/<study>/results/, and `restore` rebuilds a missing run folder from that copy, so a study continues
on another machine where it stopped and its report never depends on runs/ alone. Commit an
archived checkpoint once, when you stop for the day, not after every piece: each committed
version of it stays in the history.
"""
import gzip
import json
import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np


def load_series(folder):
    """The folder's series.csv as a structured array (None when it has no complete row yet). A row
    that a running program is still writing (no newline yet) is left out."""
    path = folder / "series.csv"
    if not path.is_file():
        return None
    lines = path.read_text().split("\n")[:-1]  # the text after the last newline is not a whole row
    if len(lines) < 2:
        return None
    data = np.genfromtxt(lines, delimiter=",", names=True)
    return np.atleast_1d(data) if data.size else None


def pieces(folder):
    """The pieces logged so far, oldest first."""
    path = folder / "pieces.jsonl"
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()] if path.is_file() else []


CHECKPOINT = "checkpoint.gfc"
PACKED = CHECKPOINT + ".gz"  # how an archive keeps it
ARCHIVED = ("series.csv", "surface.csv", "summary.json", "pieces.jsonl", "end_snapshot.json", "log.txt")


def archive(folder, dest, finished, pictures=(), extra=()):
    """Copies the case's result files, the `extra` files of the folder and the named pictures (file
    names under folder/pictures) into dest; an unfinished case also keeps its checkpoint there, a
    finished one drops it."""
    if not (folder / "series.csv").is_file():
        return
    dest.mkdir(parents=True, exist_ok=True)
    for name in tuple(ARCHIVED) + tuple(extra):
        if (folder / name).is_file():
            shutil.copy2(folder / name, dest / name)
    for name in pictures:
        if (folder / "pictures" / name).is_file():
            (dest / "pictures").mkdir(exist_ok=True)
            shutil.copy2(folder / "pictures" / name, dest / "pictures" / name)
    ckpt = folder / "checkpoints" / CHECKPOINT
    kept = dest / "checkpoints"
    if finished or not ckpt.is_file():
        shutil.rmtree(kept, ignore_errors=True)
    else:
        kept.mkdir(exist_ok=True)
        pack(ckpt, kept / PACKED)
        (kept / CHECKPOINT).unlink(missing_ok=True)  # an older archive's uncompressed copy


def pack(src, dst):
    """gzip of src written to dst atomically; no name or time in the header, so the same checkpoint
    always packs to the same bytes (git sees no change)."""
    tmp = dst.with_name(dst.name + ".tmp")
    with open(src, "rb") as fin, open(tmp, "wb") as raw:
        with gzip.GzipFile(filename="", mode="wb", fileobj=raw, mtime=0, compresslevel=6) as fout:
            shutil.copyfileobj(fin, fout, 1 << 20)
    os.replace(tmp, dst)


def restore(folder, dest):
    """Rebuilds a run folder that is missing (a new checkout) from its archive, unpacking its
    checkpoint; a folder that exists is left alone."""
    if folder.exists() or not (dest / "series.csv").is_file():
        return
    shutil.copytree(dest, folder)
    packed = folder / "checkpoints" / PACKED
    if packed.is_file():
        with gzip.open(packed, "rb") as fin, open(folder / "checkpoints" / CHECKPOINT, "wb") as fout:
            shutil.copyfileobj(fin, fout, 1 << 20)
        packed.unlink()
    print(f"{folder.name}: restored from {dest}", file=sys.stderr)


def wait_or_stop(p, deadline, folder, stop, poll_s):
    """Waits for the process to exit; SIGINT (it stops after the step in flight and writes its
    checkpoint) at the deadline or once stop(series) holds. Returns what stopped it: "budget",
    "stop test" or None (it ended by itself)."""
    while True:
        left = deadline - time.time()
        try:
            p.wait(timeout=max(0.0, min(left, poll_s) if stop else left))
            return None
        except subprocess.TimeoutExpired:
            pass
        reason = "budget" if time.time() >= deadline else None
        if reason is None and stop is not None:
            s = load_series(folder)
            reason = "stop test" if s is not None and stop(s) else None
        if reason is not None:
            p.send_signal(signal.SIGINT)
            p.wait()  # the step in flight, then its checkpoint
            return reason


def clear_for_fresh_start(folder):
    """Empties the folder of an earlier attempt that left no checkpoint (nothing to go on from), so that
    a fresh run may start in it; returns the texts of its log.txt and pieces.jsonl, which are kept."""
    if not folder.is_dir() or not any(folder.iterdir()):
        return {}
    kept = {n: (folder / n).read_text() for n in ("log.txt", "pieces.jsonl") if (folder / n).is_file()}
    shutil.rmtree(folder)
    return kept


def run_piece(name, binary, scene, folder, overrides, threads, budget_s, done, stop=None, poll_s=20.0):
    """Runs one piece of the case unless done(series) says it is finished; returns the piece's record
    (None when there was nothing to do). With `stop`, the piece is also ended (SIGINT, so with its
    checkpoint) once stop(series) holds, read every poll_s seconds."""
    ckpt = folder / "checkpoints" / CHECKPOINT
    cmd = [str(binary), "run", str(scene), "--out", str(folder), "--threads", str(threads), "--quiet"]
    for o in overrides:
        cmd += ["--set", o]
    if ckpt.is_file():
        s = load_series(folder)
        if s is not None and done(s):
            print(f"{name}: already done", file=sys.stderr)
            return None
        cmd += ["--resume", str(ckpt)]
    kept = clear_for_fresh_start(folder) if not ckpt.is_file() else {}
    folder.mkdir(parents=True, exist_ok=True)
    print(f"{name}: {' '.join(cmd)}", file=sys.stderr)
    t0 = time.time()
    # grainflow refuses a fresh run into a folder that holds files, so a fresh piece logs beside the
    # folder and the log joins it afterwards; a resumed piece logs in it.
    log_path = folder / "log.txt" if ckpt.is_file() else folder.parent / f".{folder.name}.log.txt"
    with open(log_path, "a") as log:
        p = subprocess.Popen(cmd, stdout=log, stderr=log)
        stopped = wait_or_stop(p, t0 + budget_s, folder, stop, poll_s)
    if log_path != folder / "log.txt":
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "log.txt").write_text(kept.get("log.txt", "") + log_path.read_text())
        log_path.unlink()
        if "pieces.jsonl" in kept:
            (folder / "pieces.jsonl").write_text(kept["pieces.jsonl"])
    if not (folder / "summary.json").is_file():  # refused before it ran: the log says why
        tail = (folder / "log.txt").read_text().splitlines()[-3:]
        print(f"{name}: grainflow exited with status {p.returncode} before running:\n  " + "\n  ".join(tail),
              file=sys.stderr)
        return None
    summary = json.loads((folder / "summary.json").read_text())
    piece = {
        "status": summary.get("status"),
        "rc": p.returncode,
        "steps_total": summary.get("steps"),
        "steps": summary.get("steps_this_run"),
        "wall_seconds": summary.get("wall_seconds"),
        "settle_wall_seconds": summary.get("settle", {}).get("wall_seconds", 0.0),
        "total_wall_seconds": time.time() - t0,
        "particle_steps_per_second": summary.get("particle_steps_per_second"),
        "threads": threads,
        "stopped_by": stopped,
        "date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    }
    with open(folder / "pieces.jsonl", "a") as f:
        f.write(json.dumps(piece) + "\n")
    print(f"{name}: {piece}", file=sys.stderr)
    return piece
