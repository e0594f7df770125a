"""Reading the VTK PolyData frames grainflow writes (raw appended data, UInt64 block headers).

`read_vtp` needs no numpy (the table scripts run where numpy may be missing); `appended_arrays` gives
the raw blocks that `grainflow.outputs.read_frame` turns into numpy arrays.
"""
import pathlib
import re
import struct

_TYPES = {"Float64": ("d", 8), "Int64": ("q", 8), "Int32": ("i", 4)}
_ARRAY = re.compile(r'<DataArray type="(\w+)" Name="(\w+)" NumberOfComponents="(\d+)" format="appended" '
                    r'offset="(\d+)"')
_SECTION = re.compile(r"<(PointData|Points|Verts|CellData|Lines|Strips|Polys)\b[^>]*?(/?)>")


def appended_arrays(path):
    """The header of one .vtp and its arrays: (number of points, byte order code '<' or '>', list of
    dicts with name, type, components, section (PointData, Points, Verts, ...) and the array's raw bytes)."""
    raw = pathlib.Path(path).read_bytes()
    head_end = raw.index(b"<AppendedData")
    text = raw[:head_end].decode()
    start = raw.index(b"_", raw.index(b">", head_end)) + 1
    n = int(re.search(r'NumberOfPoints="(\d+)"', text).group(1))
    order = ">" if 'byte_order="BigEndian"' in text else "<"
    sections = []  # (start, name) of each opening tag, to tell which section an array sits in
    for m in _SECTION.finditer(text):
        if not m.group(2):
            sections.append((m.start(), m.group(1)))
    arrays = []
    for m in _ARRAY.finditer(text):
        kind, name, comps, offset = m.group(1), m.group(2), int(m.group(3)), int(m.group(4))
        if kind not in _TYPES:
            raise ValueError(f"{path}: array {name} has type {kind}, which grainflow does not write")
        (nbytes,) = struct.unpack_from(order + "Q", raw, start + offset)
        section = None
        for pos, sec in sections:
            if pos < m.start():
                section = sec
        body = raw[start + offset + 8:start + offset + 8 + nbytes]
        arrays.append({"name": name, "type": kind, "components": comps, "section": section, "bytes": body})
    return n, order, arrays


def read_vtp(path):
    """The point arrays of one .vtp file as {name: [values]}: a scalar array as a list of numbers, a
    vector array (and 'Points') as a list of tuples. Needs no numpy."""
    n, order, arrays = appended_arrays(path)
    out = {}
    for a in arrays:
        code, width = _TYPES[a["type"]]
        comps = a["components"]
        values = struct.unpack_from(f"{order}{len(a['bytes']) // width}{code}", a["bytes"])
        out[a["name"]] = [tuple(values[i * comps:(i + 1) * comps]) for i in range(n)] if comps > 1 else list(values)
    return out
