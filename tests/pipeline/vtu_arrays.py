"""The named arrays of a VTU file as our writer lays it out, for tests: numpy arrays shaped
(tuples, components), in any of the three encodings. Independent of the C++ reader. (meshio 5
reads ASCII and base64 files but misreads raw appended files with several arrays.)"""
import base64
import re
from pathlib import Path

import numpy as np

TYPES = {"Float64": "<f8", "Float32": "<f4", "Int32": "<i4", "Int64": "<i8", "UInt8": "u1",
         "UInt32": "<u4", "UInt64": "<u8"}


def read_arrays(path):
    raw = Path(path).read_bytes()
    cut = raw.find(b"<AppendedData")
    xml = raw[:cut if cut >= 0 else len(raw)].decode()
    header = np.dtype(TYPES[re.search(r'header_type="(\w+)"', xml).group(1)])
    appended = raw[raw.index(b"_", cut) + 1:] if cut >= 0 else b""
    arrays = {}
    for m in re.finditer(r"<DataArray([^>]*)>([^<]*)", xml):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        dtype = np.dtype(TYPES[attrs["type"]])
        if attrs["format"] == "ascii":
            values = np.array(m.group(2).split(), dtype=dtype)
        else:
            # (byte count, values): inline base64, or raw bytes at the offset of the appended data
            block = base64.b64decode(m.group(2)) if attrs["format"] == "binary" else appended[int(attrs["offset"]):]
            count = int(np.frombuffer(block[:header.itemsize], header)[0])
            values = np.frombuffer(block[header.itemsize:header.itemsize + count], dtype)
        arrays[attrs.get("Name", "Points")] = values.reshape(-1, int(attrs.get("NumberOfComponents", 1)))
    return arrays
