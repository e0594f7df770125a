"""grainflow.run.run_scene against a stand-in binary: its command line, the Run it returns, and a
failing run's stderr in the error."""
import json
import os
import sys
import unittest
from pathlib import Path
from unittest import mock

from grainflow.outputs import Run
from grainflow.run import RunError, command, default_binary, run_scene
try:
    from .helpers import FakeBinaryTest
except ImportError:  # run as a script from python/tests
    from helpers import FakeBinaryTest

# The stand-in for `grainflow run`: records its arguments, writes a series and a summary, and with
# --set fail=true says why on stderr and exits 1 (as grainflow does on bad input) after writing nothing.
FAKE = r'''
import json, sys
from pathlib import Path
a = sys.argv[1:]
if "fail=true" in a:
    print("tiny.toml:3: run.dt: must be > 0 (set run.dt = 1e-5)", file=sys.stderr)
    sys.exit(1)
out = Path(a[a.index("--out") + 1])
out.mkdir(parents=True, exist_ok=True)
(out / "args.json").write_text(json.dumps(a))
(out / "series.csv").write_text("time,contacts\n0,1\n0.5,2\n")
(out / "summary.json").write_text(json.dumps({"status": "completed", "steps": 5}))
if "unstable=true" in a:
    print("step 3: the run became unstable", file=sys.stderr)
    sys.exit(3)
'''


class RunSceneTest(FakeBinaryTest):
    FAKE = FAKE
    PREFIX = "grainflow_run_"

    def args(self, run):
        return json.loads((run.folder / "args.json").read_text())

    def test_runs_with_overrides_and_returns_the_run(self):
        out = self.dir / "out"
        run = run_scene("scenes/tiny.toml", out, sets=["run.dt=1e-5", "wall.0.omega=2"], steps=5, threads=2,
                        binary=self.binary)
        self.assertIsInstance(run, Run)
        self.assertEqual(run.folder, out)
        self.assertEqual(self.args(run), ["run", "scenes/tiny.toml", "--out", str(out), "--set", "run.dt=1e-5",
                                          "--set", "wall.0.omega=2", "--steps", "5", "--threads", "2", "--quiet"])
        self.assertEqual(run.series["contacts"].tolist(), [1.0, 2.0])
        self.assertEqual(run.status, "completed")

    def test_plain_command_and_dict_of_overrides(self):
        run = run_scene("tiny.toml", self.dir / "plain", binary=self.binary)
        self.assertEqual(self.args(run), ["run", "tiny.toml", "--out", str(self.dir / "plain"), "--quiet"])
        cmd = command("tiny.toml", "o", sets={"run.dt": 1e-5}, binary="gf", resume="o/checkpoints/checkpoint.gfc",
                      quiet=False)
        self.assertEqual(cmd, ["gf", "run", "tiny.toml", "--out", "o", "--set", "run.dt=1e-05",
                               "--resume", "o/checkpoints/checkpoint.gfc"])
        self.assertEqual(command("tiny.toml", "o", binary="gf", overwrite=True)[-2:], ["--overwrite", "--quiet"])

    def test_failure_raises_with_stderr(self):
        with self.assertRaises(RunError) as e:
            run_scene("tiny.toml", self.dir / "bad", sets=["fail=true"], binary=self.binary)
        self.assertEqual(e.exception.returncode, 1)
        self.assertIn("run.dt: must be > 0", str(e.exception))
        self.assertIn("run.dt: must be > 0", e.exception.stderr)
        # without check, a run that wrote its folder is returned; one that wrote nothing still raises
        run = run_scene("tiny.toml", self.dir / "unstable", sets=["unstable=true"], binary=self.binary, check=False)
        self.assertEqual(run.status, "completed")
        with self.assertRaises(RunError):
            run_scene("tiny.toml", self.dir / "bad", sets=["fail=true"], binary=self.binary, check=False)
        # refused (status 1 or 2) into a folder of an earlier run: raises, not the older run's folder
        with self.assertRaises(RunError):
            run_scene("tiny.toml", self.dir / "unstable", sets=["fail=true"], binary=self.binary, check=False)
        with self.assertRaisesRegex(RunError, "became unstable"):
            run_scene("tiny.toml", self.dir / "unstable", sets=["unstable=true"], binary=self.binary)

    def test_binary_from_the_environment(self):
        with mock.patch.dict(os.environ, {"GRAINFLOW_BINARY": str(self.binary)}):
            self.assertEqual(default_binary(), self.binary)
            run = run_scene("tiny.toml", self.dir / "env")
        self.assertEqual(run.summary["steps"], 5)
        with mock.patch.dict(os.environ):
            os.environ.pop("GRAINFLOW_BINARY", None)
            self.assertEqual(default_binary(), Path(__file__).resolve().parents[2] / "build" / "grainflow")

    def test_missing_binary(self):
        with self.assertRaisesRegex(FileNotFoundError, "GRAINFLOW_BINARY"):
            run_scene("tiny.toml", self.dir / "x", binary=self.dir / "nothing")


if __name__ == "__main__":
    unittest.main()
