"""A minimal OpenEXR writer for tests: one scan-line part, no compression, FLOAT channels, and
optional double and string attributes; enough to hand gonio height maps it did not write
(OpenEXR 2 file layout: magic, version, header attributes, line offsets, scan lines)."""
import struct

import numpy as np


def _attribute(name, kind, payload):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(payload)) + \
        payload


def write_exr(path, channels, doubles=None, strings=None):
    """channels: {name: 2-D float32 array (rows, columns)}, all the same shape."""
    names = sorted(channels)
    h, w = np.asarray(channels[names[0]]).shape
    chlist = b"".join(n.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for n in names) + \
        b"\0"
    header = _attribute("channels", "chlist", chlist)
    header += _attribute("compression", "compression", b"\0")
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header += _attribute("dataWindow", "box2i", box)
    header += _attribute("displayWindow", "box2i", box)
    header += _attribute("lineOrder", "lineOrder", b"\0")
    header += _attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
    header += _attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
    header += _attribute("screenWindowWidth", "float", struct.pack("<f", 1.0))
    for k, v in (doubles or {}).items():
        header += _attribute(k, "double", struct.pack("<d", v))
    for k, v in (strings or {}).items():
        header += _attribute(k, "string", v.encode())
    header += b"\0"
    start = 8 + len(header) + 8 * h
    line = 8 + 4 * w * len(names)
    offsets = struct.pack(f"<{h}Q", *[start + y * line for y in range(h)])
    body = b""
    for y in range(h):
        data = b"".join(np.asarray(channels[n], dtype="<f4")[y].tobytes() for n in names)
        body += struct.pack("<ii", y, len(data)) + data
    with open(path, "wb") as f:
        f.write(struct.pack("<ii", 20000630, 2) + header + offsets + body)
