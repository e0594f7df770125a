"""Reading the VTK PolyData frames grainflow writes (raw appended data, UInt64 block headers)."""
import pathlib
import re
import struct

_TYPES = {"Float64": ("d", 8), "Int64": ("q", 8), "Int32": ("i", 4)}


def read_vtp(path):
    """The point arrays of one .vtp file as {name: [values]}: a scalar array as a list of numbers, a
    vector array (and 'Points') as a list of tuples. Needs no numpy."""
    raw = pathlib.Path(path).read_bytes()
    head_end = raw.index(b"<AppendedData")
    text = raw[:head_end].decode()
    start = raw.index(b"_", raw.index(b">", head_end)) + 1
    n = int(re.search(r'NumberOfPoints="(\d+)"', text).group(1))
    out = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)" NumberOfComponents="(\d+)" format="appended" '
                         r'offset="(\d+)"', text):
        kind, name, comps, offset = m.group(1), m.group(2), int(m.group(3)), int(m.group(4))
        code, width = _TYPES[kind]
        (nbytes,) = struct.unpack_from("<Q", raw, start + offset)
        values = struct.unpack_from(f"<{nbytes // width}{code}", raw, start + offset + 8)
        out[name] = [tuple(values[i * comps:(i + 1) * comps]) for i in range(n)] if comps > 1 else list(values)
    return out
