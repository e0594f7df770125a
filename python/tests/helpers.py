"""Small run-folder files written for the tests: a series, a summary, a final state, a two-point frame."""
import json
import stat
import struct
import sys
import tempfile
import unittest
from pathlib import Path

SERIES = ("time,angle,ke_translational,contacts,lacey_index,surface_angle\n"
          "0,0,1.5,10,nan,nan\n"
          "0.01,0.005,1.25,12,0.5,0.3\n"
          "0.02,0.01,1,14,0.75,-nan\n")
SUMMARY = {"status": "completed", "scene": "tiny.toml", "grains": 2, "steps": 200,
           "final": {"lacey_index": 0.75, "surface_angle": None}}
FINAL_STATE = ("id,type,diameter,x,y,z,vx,vy,vz,wx,wy,wz\n"
               "7,1,0.002,0.1,0.2,0.3,0,0,-1,0,0,0\n"
               "9,2,0.004,-0.1,-0.2,-0.3,1e-3,0,0,0,5,0\n")
RESIDENCE = ("id,species,mass,entry_time,exit_time,residence_time\n"
             "109,0,0.0078,11.5,49.1564,37.6564\n"
             "3,1,0.0029,nan,12,nan\n")
LAYERS = "time,distance,vc,lacey,fraction_a,cells,grains\n19.5,0.025,0.42,0.93,0.29,5,377\n"

# The two grains of the frame, as grainflow's writer lays them out (systems/output/vtk_frames.cpp).
POINTS = [(0.1, 0.2, 0.3), (-0.1, -0.2, -0.3)]
IDS = [7, 9]
SPECIES = [0, 1]  # 0-based, as the frames write them
RADII = [0.001, 0.002]
VELOCITY = [(0.0, 0.0, -1.0), (1e-3, 0.0, 0.0)]


def vtp_bytes():
    arrays = []  # (section, VTK type, name, components, struct code, values)
    arrays.append(("PointData", "Int64", "id", 1, "q", IDS))
    arrays.append(("PointData", "Int32", "species", 1, "i", SPECIES))
    arrays.append(("PointData", "Float64", "radius", 1, "d", RADII))
    arrays.append(("PointData", "Float64", "velocity", 3, "d", [c for v in VELOCITY for c in v]))
    arrays.append(("Points", "Float64", "Points", 3, "d", [c for p in POINTS for c in p]))
    arrays.append(("Verts", "Int64", "connectivity", 1, "q", [0, 1]))
    arrays.append(("Verts", "Int64", "offsets", 1, "q", [1, 2]))
    blob = b""
    xml = {"PointData": "", "Points": "", "Verts": ""}
    for section, kind, name, comps, code, values in arrays:
        xml[section] += (f'        <DataArray type="{kind}" Name="{name}" NumberOfComponents="{comps}" '
                         f'format="appended" offset="{len(blob)}"/>\n')
        body = struct.pack(f"<{len(values)}{code}", *values)
        blob += struct.pack("<Q", len(body)) + body
    head = ('<?xml version="1.0"?>\n'
            '<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">\n'
            '  <PolyData>\n'
            '    <Piece NumberOfPoints="2" NumberOfVerts="2" NumberOfLines="0" NumberOfStrips="0" NumberOfPolys="0">\n'
            '      <PointData Scalars="radius" Vectors="velocity">\n' + xml["PointData"] + '      </PointData>\n'
            '      <Points>\n' + xml["Points"] + '      </Points>\n'
            '      <Verts>\n' + xml["Verts"] + '      </Verts>\n'
            '    </Piece>\n  </PolyData>\n  <AppendedData encoding="raw">\n   _')
    return head.encode() + blob + b"\n  </AppendedData>\n</VTKFile>\n"


def pvd_text(entries):
    rows = "".join(f'    <DataSet timestep="{t}" group="" part="0" file="{f}"/>\n' for t, f in entries)
    return ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="1.0" byte_order="LittleEndian" '
            'header_type="UInt64">\n  <Collection>\n' + rows + '  </Collection>\n</VTKFile>\n')


def write_run(folder, optional=True):
    """A run folder with series.csv, summary.json, final_state.csv and two frames; with optional, also
    residence.csv, layers.csv and surface.csv."""
    folder = Path(folder)
    (folder / "frames").mkdir(parents=True, exist_ok=True)
    (folder / "series.csv").write_text(SERIES)
    (folder / "summary.json").write_text(json.dumps(SUMMARY))
    (folder / "final_state.csv").write_text(FINAL_STATE)
    (folder / "frames" / "frame_000000.vtp").write_bytes(vtp_bytes())
    (folder / "frames" / "frame_000001.vtp").write_bytes(vtp_bytes())
    (folder / "frames.pvd").write_text(pvd_text([(0, "frames/frame_000000.vtp"), (0.01, "frames/frame_000001.vtp")]))
    if optional:
        (folder / "residence.csv").write_text(RESIDENCE)
        (folder / "layers.csv").write_text(LAYERS)
        (folder / "surface.csv").write_text("time,angle,surface_angle,surface_level\n0,0,nan,0.01\n")
    return folder


class FakeBinaryTest(unittest.TestCase):
    """A temporary folder holding `grainflow`, a Python stand-in whose body is the class's FAKE text."""

    FAKE = ""
    PREFIX = "grainflow_test_"

    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix=self.PREFIX)
        self.dir = Path(self._tmp.name)
        self.binary = self.dir / "grainflow"
        self.binary.write_text(f"#!{sys.executable}\n{self.FAKE}")
        self.binary.chmod(self.binary.stat().st_mode | stat.S_IXUSR)

    def tearDown(self):
        self._tmp.cleanup()
