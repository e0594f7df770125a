"""grainflow.outputs on a run folder written here: columns, nan, ids as integers, a row still being
written, missing files named, the frames of frames.pvd and a two-point .vtp."""
import json
import math
import tempfile
import unittest
from pathlib import Path

import numpy as np

from grainflow.outputs import MissingOutputError, Run, read_csv, read_frame, read_pvd, rows_of

try:
    from . import helpers
except ImportError:  # run from inside python/tests
    import helpers


class RunFolderTest(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="grainflow_outputs_")
        self.dir = Path(self._tmp.name)
        self.run = Run(helpers.write_run(self.dir / "run"))

    def tearDown(self):
        self._tmp.cleanup()

    def test_series_columns_and_nan(self):
        s = self.run.series
        self.assertEqual(list(s), ["time", "angle", "ke_translational", "contacts", "lacey_index", "surface_angle"])
        np.testing.assert_allclose(s["time"], [0, 0.01, 0.02])
        np.testing.assert_allclose(s["ke_translational"], [1.5, 1.25, 1.0])
        self.assertEqual(s["contacts"].dtype, np.float64)
        self.assertTrue(math.isnan(s["lacey_index"][0]))
        self.assertEqual(s["lacey_index"][2], 0.75)
        self.assertTrue(np.isnan(s["surface_angle"][[0, 2]]).all())

    def test_series_reread_when_the_file_grows(self):
        self.assertEqual(len(self.run.series["time"]), 3)
        with open(self.run.folder / "series.csv", "a") as f:
            f.write("0.03,0.015,0.5,16,0.8,0.1\n0.04,0.02")  # the second row is still being written
        s = self.run.series
        self.assertEqual(len(s["time"]), 4)
        self.assertEqual(s["time"][-1], 0.03)

    def test_header_only_series(self):
        (self.run.folder / "series.csv").write_text("time,angle\n")
        s = read_csv(self.run.folder / "series.csv")
        self.assertEqual(list(s), ["time", "angle"])
        self.assertEqual(len(s["time"]), 0)

    def test_ragged_row_is_an_error(self):
        (self.dir / "bad.csv").write_text("a,b\n1,2\n3\n")
        with self.assertRaisesRegex(ValueError, r"bad.csv:3"):
            read_csv(self.dir / "bad.csv")

    def test_walls_by_wall(self):
        (self.run.folder / "walls.csv").write_text(
            "time,drum.fx,drum.fy,drum.fz,drum.tx,drum.ty,drum.tz,drum.power,box-y.fx,box-y.fy,box-y.fz,"
            "box-y.tx,box-y.ty,box-y.tz,box-y.power\n0,1,2,3,4,5,6,7,0,-0.5,0,0,0,0,0\n0.1,1,2,3,4,5,-6,8,0,-0.25,0,0,0,0,0\n")
        w = self.run.walls
        self.assertEqual(list(w), ["drum", "box-y"])
        np.testing.assert_allclose(w["drum"]["tz"], [6, -6])
        np.testing.assert_allclose(w["box-y"]["fy"], [-0.5, -0.25])
        np.testing.assert_allclose(w["box-y"]["time"], [0, 0.1])

    def test_summary(self):
        self.assertEqual(self.run.summary, helpers.SUMMARY)
        self.assertEqual(self.run.status, "completed")
        summary = dict(helpers.SUMMARY, status="interrupted")
        (self.run.folder / "summary.json").write_text(json.dumps(summary, indent=1))
        self.assertEqual(self.run.status, "interrupted")

    def test_final_state(self):
        g = self.run.final_state()
        self.assertEqual(list(g)[:6], ["id", "type", "diameter", "x", "y", "z"])
        self.assertEqual(g["id"].dtype, np.int64)
        self.assertEqual(g["id"].tolist(), [7, 9])
        self.assertEqual(g["type"].tolist(), [1, 2])
        np.testing.assert_allclose(g["vx"], [0, 1e-3])
        np.testing.assert_allclose(g["wy"], [0, 5])

    def test_rows_of(self):
        rows = rows_of(self.run.final_state())
        self.assertEqual(len(rows), 2)
        self.assertEqual(rows[1]["id"], 9)
        self.assertIsInstance(rows[1]["id"], int)
        self.assertIsInstance(rows[1]["vx"], float)
        self.assertEqual(rows[1]["vx"], 1e-3)
        (self.dir / "t.csv").write_text("a,name\n1.5,moving\n")
        self.assertEqual(rows_of(read_csv(self.dir / "t.csv")), [{"a": 1.5, "name": "moving"}])
        self.assertEqual(rows_of({}), [])

    def test_residence_layers_surface(self):
        r = self.run.residence()
        self.assertEqual(r["species"].tolist(), [0, 1])
        self.assertTrue(math.isnan(r["entry_time"][1]))
        self.assertAlmostEqual(r["residence_time"][0], 37.6564)
        self.assertEqual(self.run.layers()["grains"].tolist(), [377.0])
        self.assertTrue(math.isnan(self.run.surface["surface_angle"][0]))

    def test_missing_files_are_named(self):
        bare = Run(helpers.write_run(self.dir / "bare", optional=False))
        for call, name in [(bare.residence, "residence.csv"), (bare.layers, "layers.csv"),
                           (lambda: bare.surface, "surface.csv")]:
            with self.assertRaises(MissingOutputError) as e:
                call()
            self.assertIn(name, str(e.exception))
            self.assertIsInstance(e.exception, FileNotFoundError)
        (bare.folder / "frames.pvd").unlink()
        with self.assertRaisesRegex(MissingOutputError, r"frames\.pvd.*frame_interval"):
            bare.frames()
        with self.assertRaisesRegex(FileNotFoundError, "no such run folder"):
            Run(self.dir / "nowhere")

    def test_frames(self):
        frames = self.run.frames()
        self.assertEqual([t for t, _ in frames], [0.0, 0.01])
        self.assertEqual(frames[1][1], self.run.folder / "frames" / "frame_000001.vtp")
        self.assertEqual(read_pvd(self.run.folder / "frames.pvd"), frames)

    def test_read_frame(self):
        points, data = read_frame(self.run.frames()[0][1])
        np.testing.assert_array_equal(points, helpers.POINTS)
        self.assertEqual(sorted(data), ["id", "radius", "species", "velocity"])  # no Points, no Verts arrays
        self.assertEqual(data["id"].dtype, np.int64)
        self.assertEqual(data["id"].tolist(), helpers.IDS)
        self.assertEqual(data["species"].dtype, np.int32)
        self.assertEqual(data["species"].tolist(), helpers.SPECIES)
        np.testing.assert_array_equal(data["radius"], helpers.RADII)
        self.assertEqual(data["velocity"].shape, (2, 3))
        np.testing.assert_array_equal(data["velocity"], helpers.VELOCITY)
        last = self.run.frame()
        np.testing.assert_array_equal(last.points, points)

    def test_read_frame_of_ranks(self):
        folder = self.run.folder / "frames"
        (folder / "frame_000000.pvtp").write_text(
            '<?xml version="1.0"?>\n<VTKFile type="PPolyData" version="1.0">\n  <PPolyData GhostLevel="0">\n'
            '    <Piece Source="frame_000000.vtp"/>\n    <Piece Source="frame_000001.vtp"/>\n'
            '  </PPolyData>\n</VTKFile>\n')
        points, data = read_frame(folder / "frame_000000.pvtp")
        self.assertEqual(points.shape, (4, 3))
        self.assertEqual(data["id"].tolist(), helpers.IDS * 2)

    def test_missing_frame_file(self):
        with self.assertRaisesRegex(MissingOutputError, "frame_000009.vtp"):
            read_frame(self.run.folder / "frames" / "frame_000009.vtp")


if __name__ == "__main__":
    unittest.main()
