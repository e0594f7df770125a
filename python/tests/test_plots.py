"""grainflow.plots on a run folder written here: the series' lines, the walls' lines by wall, a frame's
discs and the summary figure saved as a PNG."""
import tempfile
import unittest
from pathlib import Path

import matplotlib
matplotlib.use("Agg")

from grainflow import plots
from grainflow.outputs import Run

try:
    from . import helpers
except ImportError:  # run from inside python/tests
    import helpers

WALLS = ("time,drum.fx,drum.fy,drum.fz,drum.tx,drum.ty,drum.tz,drum.power,lid.fx,lid.fy,lid.fz,lid.tx,lid.ty,lid.tz,"
         "lid.power\n0,0,-1,0,0,0,0.1,0.3,0,0,0,0,0,0,0\n0.01,0,-1,0,0,0,0.2,0.6,0,0.5,0,0,0,0,0.1\n")


class PlotsTest(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="grainflow_plots_")
        self.run = Run(helpers.write_run(Path(self._tmp.name) / "run"))
        (self.run.folder / "walls.csv").write_text(WALLS)

    def tearDown(self):
        self._tmp.cleanup()

    def test_series_lines(self):
        ax = plots.series(self.run, ["ke_translational", "contacts"])
        self.assertEqual(len(ax.lines), 2)
        self.assertEqual(list(ax.lines[0].get_ydata()), [1.5, 1.25, 1.0])
        with self.assertRaisesRegex(KeyError, "no column 'nothing'"):
            plots.series(self.run, "nothing")

    def test_walls_by_wall(self):
        ax = plots.walls(self.run, "power")
        self.assertEqual([l.get_label() for l in ax.lines], ["drum", "lid"])
        self.assertEqual(list(ax.lines[0].get_ydata()), [0.3, 0.6])
        self.assertEqual(ax.get_ylabel(), "power (W)")

    def test_frame_discs(self):
        ax = plots.frame(self.run, axis=2)
        self.assertEqual(len(ax.collections), 1)
        self.assertEqual(len(ax.collections[0].get_offsets()), 2)

    def test_summary_figure_saved(self):
        out = Path(self._tmp.name) / "summary.png"
        self.assertEqual(plots.main([str(self.run.folder), "--out", str(out)]), 0)
        self.assertGreater(out.stat().st_size, 1000)
        self.assertEqual(out.read_bytes()[:8], b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main()
