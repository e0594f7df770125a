"""grainflow.vtp's numpy-free reader on a two-point frame, and a package import that needs no numpy."""
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

from grainflow.vtp import read_vtp

try:
    from . import helpers
except ImportError:
    import helpers


class VtpTest(unittest.TestCase):
    def test_lists_and_tuples(self):
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "frame.vtp"
            path.write_bytes(helpers.vtp_bytes())
            a = read_vtp(path)
        self.assertEqual(a["Points"], helpers.POINTS)
        self.assertEqual(a["id"], helpers.IDS)
        self.assertEqual(a["species"], helpers.SPECIES)
        self.assertEqual(a["radius"], helpers.RADII)
        self.assertEqual(a["velocity"], helpers.VELOCITY)
        self.assertEqual(a["connectivity"], [0, 1])
        self.assertEqual(a["offsets"], [1, 2])

    def test_no_numpy_needed(self):
        # The table scripts import grainflow.vtp where numpy may be missing: neither the package nor
        # this module may import it.
        code = ("import sys; sys.modules['numpy'] = None\n"
                "import grainflow, grainflow.vtp\nprint(grainflow.__version__)")
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           cwd=Path(__file__).resolve().parents[1])
        self.assertEqual(p.returncode, 0, p.stderr)


if __name__ == "__main__":
    unittest.main()
