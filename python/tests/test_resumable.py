"""grainflow.resumable's pieces of a stand-in run, its archive and restore, and the command line of
`python3 -m grainflow.long_run` (tests/resumable_test.py checks budgets and stop tests at length)."""
import contextlib
import gzip
import io
import json
import os
import subprocess
import sys
import unittest
from pathlib import Path

import grainflow.resumable as r
try:
    from .helpers import FakeBinaryTest
except ImportError:  # run as a script from python/tests
    from helpers import FakeBinaryTest

PYTHON_DIR = Path(__file__).resolve().parents[1]

# The stand-in: rows=N series rows, a checkpoint holding the rows done, a completed summary.
FAKE = r'''
import json, sys
from pathlib import Path
a = sys.argv[1:]
out = Path(a[a.index("--out") + 1])
start = int(Path(a[a.index("--resume") + 1]).read_text()) if "--resume" in a else 0
if "--resume" not in a and out.is_dir() and any(out.iterdir()):  # as grainflow refuses it
    print("the output folder already holds files", file=sys.stderr)
    sys.exit(1)
print(f"ran from {start}", file=sys.stderr)
out.mkdir(parents=True, exist_ok=True)
with open(out / "series.csv", "a") as f:
    if start == 0:
        f.write("time,angle\n")
    for k in range(start + 1, start + 4):
        f.write(f"{k / 10},{k / 10}\n")
(out / "checkpoints").mkdir(exist_ok=True)
(out / "checkpoints" / "checkpoint.gfc").write_text(str(start + 3))
(out / "summary.json").write_text(json.dumps({"status": "completed", "steps": start + 3, "steps_this_run": 3,
                                              "wall_seconds": 0.1}))
(out / "layers.csv").write_text("time,distance\n1,0.1\n")
'''


class ResumableTest(FakeBinaryTest):
    FAKE = FAKE
    PREFIX = "grainflow_resumable_"

    def test_piece_archive_restore(self):
        with contextlib.redirect_stderr(io.StringIO()):  # the pieces' log lines
            self.pieces_archive_restore()

    def pieces_archive_restore(self):
        folder = self.dir / "runs" / "case"
        # an earlier attempt that left only its log: the fresh piece starts in an emptied folder, log kept
        folder.mkdir(parents=True)
        (folder / "log.txt").write_text("refused: a typo\n")
        piece = r.run_piece("case", self.binary, "tiny.toml", folder, ["a=1"], 1, 30, lambda s: False)
        self.assertEqual(piece["status"], "completed")
        self.assertEqual(piece["steps"], 3)
        self.assertEqual(len(r.pieces(folder)), 1)
        r.run_piece("case", self.binary, "tiny.toml", folder, [], 1, 30, lambda s: False)  # resumes
        self.assertEqual(r.load_series(folder)["time"].tolist(), [0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
        self.assertIsNone(r.run_piece("case", self.binary, "tiny.toml", folder, [], 1, 30, lambda s: True))
        self.assertEqual((folder / "log.txt").read_text(), "refused: a typo\nran from 0\nran from 3\n")
        # a row still being written is left out
        with open(folder / "series.csv", "a") as f:
            f.write("0.7,0.")
        self.assertEqual(len(r.load_series(folder)), 6)

        dest = self.dir / "archive"
        r.archive(folder, dest, finished=False)
        with gzip.open(dest / "checkpoints" / r.PACKED, "rb") as f:
            self.assertEqual(f.read(), b"6")
        restored = self.dir / "runs" / "again"
        r.restore(restored, dest)
        self.assertEqual((restored / "checkpoints" / r.CHECKPOINT).read_text(), "6")
        self.assertFalse((restored / "checkpoints" / r.PACKED).exists())
        r.archive(folder, dest, finished=True)
        self.assertFalse((dest / "checkpoints").exists())

    def long_run(self, *args):
        env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(PYTHON_DIR), os.environ.get("PYTHONPATH", "")]))
        return subprocess.run([sys.executable, "-m", "grainflow.long_run", *map(str, args)], capture_output=True,
                              text=True, env=env, cwd=self.dir)

    def test_long_run_command_line(self):
        p = self.long_run("--help")
        self.assertEqual(p.returncode, 0, p.stderr)
        for option in ("--out", "--archive", "--set", "--keep", "--budget-minutes", "--threads", "--binary"):
            self.assertIn(option, p.stdout)
        p = self.long_run("tiny.toml", "--out", "runs/case", "--archive", "kept/case", "--set", "a=1",
                          "--keep", "layers.csv", "--budget-minutes", "1", "--binary", self.binary)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("case: completed", p.stdout)
        kept = self.dir / "kept" / "case"
        for name in ("series.csv", "summary.json", "pieces.jsonl", "layers.csv"):
            self.assertTrue((kept / name).is_file(), name)
        self.assertEqual(json.loads((kept / "summary.json").read_text())["status"], "completed")
        self.assertFalse((kept / "checkpoints").exists())
        p = self.long_run("tiny.toml", "--out", "runs/x", "--archive", "kept/x", "--binary", self.dir / "none")
        self.assertNotEqual(p.returncode, 0)
        self.assertIn("not found", p.stderr)


if __name__ == "__main__":
    unittest.main()
