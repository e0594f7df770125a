"""A grainflow run folder read into numpy arrays (the files and columns of docs/manual/running.md).

    from grainflow.outputs import Run
    run = Run("runs/drum_quick")
    t, lacey = run.series["time"], run.series["lacey_index"]
    run.summary["status"]
    grains = run.final_state()            # {"id": int array, "x": float array, ...}
    for time, path in run.frames():
        points, data = read_frame(path)   # (n, 3) positions, {"radius": (n,), "velocity": (n, 3), ...}

A CSV file becomes {column: array} in file order: float64 arrays (`nan` where the file says nan), the
ids of grains and species (`id`, `type`, `species`) int64. The row a running program is still
writing (no newline yet) is left out, so a folder can be read while its run goes on. A file the run
did not write raises MissingOutputError, naming the file and when grainflow writes it.
"""
import csv
import json
import os
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import NamedTuple

import numpy as np

from grainflow.vtp import _TYPES, appended_arrays

# When grainflow writes each optional file (docs/manual/running.md, "Outputs").
WRITTEN_WHEN = {
    "series.csv": "output.series_interval > 0",
    "surface.csv": "the scene has a drum or cylinder wall and exactly two species",
    "walls.csv": "output.series_interval > 0 and the scene has walls",
    "summary.json": "always, at the start of the run",
    "final_state.csv": "always, at the end of the run",
    "residence.csv": "the scene has an [[outlet]]",
    "layers.csv": "the scene has [analysis.layers]",
    "frames.pvd": "output.frame_interval > 0",
    "walls.pvd": "output.frame_interval > 0 and the scene has walls",
}


class MissingOutputError(FileNotFoundError):
    """A run folder lacks one of its output files."""


def _missing(folder, name):
    when = WRITTEN_WHEN.get(name)
    why = f" (grainflow writes it when {when})" if when else ""
    return MissingOutputError(f"{Path(folder) / name}: the run folder has no {name}{why}")


# Columns that name grains or species rather than measure something: int64 arrays.
ID_COLUMNS = ("id", "type", "species")


def _column(name, tokens):
    """One CSV column of text as float64 (`nan` and `inf` read as such; an id column as int64), or
    the text itself when it is not numbers."""
    col = np.asarray(tokens, dtype=str)
    for kind in ((np.int64, np.float64) if name in ID_COLUMNS else (np.float64,)):
        try:
            return col.astype(kind)
        except (ValueError, OverflowError):
            pass
    return col


def read_csv(path):
    """A CSV file with a header line as {column: numpy array} (quoted fields as the csv module reads
    them). Rows without their newline yet (being written) are left out; a file with only its header
    gives empty float arrays."""
    path = Path(path)
    if not path.is_file():
        raise _missing(path.parent, path.name)
    lines = path.read_text().split("\n")[:-1]  # the text after the last newline is not a whole row
    if not lines:
        raise ValueError(f"{path}: no header line")
    parsed = csv.reader(lines)
    names = [n.strip() for n in next(parsed)]
    rows = [row for row in parsed if row]
    for i, row in enumerate(rows):
        if len(row) != len(names):
            raise ValueError(f"{path}:{i + 2}: {len(row)} values for {len(names)} columns")
    if not rows:
        return {n: np.zeros(0) for n in names}
    columns = list(zip(*rows))
    return {n: _column(n, [v.strip() for v in c]) for n, c in zip(names, columns)}


def rows_of(table):
    """A {column: array} table (read_csv's) as a list of rows, each {column: value}: numbers as Python
    floats (ids as ints), text as str. For code that walks a file row by row."""
    names = list(table)
    n = len(table[names[0]]) if names else 0
    return [{k: table[k][i].item() for k in names} for i in range(n)]


class Frame(NamedTuple):
    """One frame's points, (n, 3), and point data, {name: (n,) or (n, components) array}."""
    points: np.ndarray
    data: dict


def _read_vtp_arrays(path):
    n, order, arrays = appended_arrays(path)
    points = np.zeros((n, 3))
    data = {}
    for a in arrays:
        code, _ = _TYPES[a["type"]]
        values = np.frombuffer(a["bytes"], dtype=np.dtype(order + code)).copy()
        if a["components"] > 1:
            values = values.reshape(-1, a["components"])
        if a["section"] == "Points":
            points = values.reshape(-1, 3)
        elif a["section"] == "PointData":
            data[a["name"]] = values
    return points, data


class WallSurface(NamedTuple):
    """The walls at one frame: points (n, 3), triangles (m, 3) of point indices, and wall (m,), each
    triangle's wall index in the order of walls.csv."""
    points: np.ndarray
    triangles: np.ndarray
    wall: np.ndarray


def read_wall_surface(path):
    """One walls/walls_NNNNNN.vtp as a WallSurface."""
    path = Path(path)
    if not path.is_file():
        raise MissingOutputError(f"{path}: no such walls file")
    n, order, arrays = appended_arrays(path)
    got = {}
    for a in arrays:
        code, width = _TYPES[a["type"]]
        got[a["name"]] = np.frombuffer(a["bytes"], dtype=np.dtype(order + code)).reshape(-1, a["components"])
    return WallSurface(got["Points"].reshape(n, 3), got["connectivity"].reshape(-1, 3), got["wall"].reshape(-1))


def read_frame(path):
    """The points and point-data arrays of one frame: a .vtp, or a .pvtp of grainflow_mpi whose
    pieces (one .vtp per rank) are joined in rank order. Returns Frame(points, data)."""
    path = Path(path)
    if not path.is_file():
        raise MissingOutputError(f"{path}: no such frame file")
    if path.suffix == ".pvtp":
        sources = [p.get("Source") for p in ET.parse(path).getroot().iter("Piece")]
        parts = [_read_vtp_arrays(path.parent / s) for s in sources]
        if not parts:
            return Frame(np.zeros((0, 3)), {})
        points = np.concatenate([p for p, _ in parts])
        data = {k: np.concatenate([d[k] for _, d in parts]) for k in parts[0][1]}
        return Frame(points, data)
    return Frame(*_read_vtp_arrays(path))


def read_pvd(path):
    """The (time, path) of each frame a .pvd collection lists, in its order; paths are made absolute
    against the .pvd's folder."""
    path = Path(path)
    if not path.is_file():
        raise _missing(path.parent, path.name)
    root = ET.parse(path).getroot()
    return [(float(d.get("timestep")), path.parent / d.get("file")) for d in root.iter("DataSet")]


class Run:
    """One run folder. `series`, `surface` and `summary` are read when first used and again when their
    file has changed since; the other files are read on each call."""

    def __init__(self, folder):
        self.folder = Path(folder)
        if not self.folder.is_dir():
            raise FileNotFoundError(f"{self.folder}: no such run folder")
        self._cache = {}

    def __repr__(self):
        return f"Run({str(self.folder)!r})"

    def path(self, name):
        """The path of one output file of the folder; MissingOutputError when there is none."""
        p = self.folder / name
        if not p.exists():
            raise _missing(self.folder, name)
        return p

    def has(self, name):
        return (self.folder / name).exists()

    def _cached(self, name, reader):
        p = self.path(name)
        st = os.stat(p)
        key = (st.st_mtime_ns, st.st_size)
        hit = self._cache.get(name)
        if hit is None or hit[0] != key:
            hit = (key, reader(p))
            self._cache[name] = hit
        return hit[1]

    @property
    def series(self):
        """series.csv: {column: array}."""
        return self._cached("series.csv", read_csv)

    @property
    def surface(self):
        """surface.csv: {column: array}."""
        return self._cached("surface.csv", read_csv)

    @property
    def walls(self):
        """walls.csv as {wall: {"time", "fx", "fy", "fz", "tx", "ty", "tz", "power": array}}: what each wall
        feels, the mean over each series row's interval."""
        def split(p):
            cols = read_csv(p)
            out = {}
            for name, values in cols.items():
                if name == "time":
                    continue
                wall, _, quantity = name.rpartition(".")
                out.setdefault(wall, {"time": cols["time"]})[quantity] = values
            return out
        return self._cached("walls.csv", split)

    @property
    def summary(self):
        """summary.json as a dict."""
        return self._cached("summary.json", lambda p: json.loads(p.read_text()))

    @property
    def status(self):
        """The summary's status: "running", "completed", "interrupted" or "failed"."""
        return self.summary.get("status")

    def final_state(self):
        """final_state.csv: {"id", "type", "diameter", "x", ..., "wz": array}."""
        return read_csv(self.path("final_state.csv"))

    def residence(self):
        """residence.csv: one entry per grain counted out ({"id", "species", "mass", ...: array})."""
        return read_csv(self.path("residence.csv"))

    def layers(self):
        """layers.csv: {"time", "distance", "vc", "lacey", ...: array}."""
        return read_csv(self.path("layers.csv"))

    def frames(self):
        """[(time, path)] of the frames frames.pvd lists."""
        return read_pvd(self.path("frames.pvd"))

    def frame(self, index=-1):
        """One frame's Frame(points, data), by its index in frames() (default the last)."""
        frames = self.frames()
        if not frames:
            raise MissingOutputError(f"{self.folder / 'frames.pvd'}: lists no frame")
        return read_frame(frames[index][1])

    def wall_surface(self, index=-1):
        """The walls at one frame of walls.pvd (default the last) as a WallSurface."""
        listed = read_pvd(self.path("walls.pvd"))
        if not listed:
            raise MissingOutputError(f"{self.folder / 'walls.pvd'}: lists no frame")
        return read_wall_surface(listed[index][1])

    def pictures(self):
        """The PNG pictures of the folder, sorted by name."""
        return sorted((self.folder / "pictures").glob("*.png"))

    def checkpoint(self):
        """The last checkpoint, checkpoints/checkpoint.gfc."""
        return self.path("checkpoints/checkpoint.gfc")
