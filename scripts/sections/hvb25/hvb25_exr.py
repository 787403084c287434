"""A small reader of the EXR frames dflab writes (io/exr.h: single-part
scanline images, NONE / ZIPS / ZIP compression, HALF / FLOAT / UINT
channels), so the report can show them without an OpenEXR Python module
(Debian has none)."""
import struct
import zlib

import numpy as np

_TYPES = {0: ("<u4", 4), 1: ("<f2", 2), 2: ("<f4", 4)}
_LINES = {0: 1, 2: 1, 3: 16}  # NONE, ZIPS, ZIP


def _attrs(buf):
    pos, out = 8, {}
    while buf[pos] != 0:
        end = buf.index(b"\0", pos)
        name = buf[pos:end].decode()
        tend = buf.index(b"\0", end + 1)
        typ = buf[end + 1:tend].decode()
        (size,) = struct.unpack_from("<i", buf, tend + 1)
        out[name] = (typ, buf[tend + 5:tend + 5 + size])
        pos = tend + 5 + size
    return out, pos + 1


def _channels(raw):
    pos, out = 0, []
    while raw[pos] != 0:
        end = raw.index(b"\0", pos)
        (ptype,) = struct.unpack_from("<i", raw, end + 1)
        out.append((raw[pos:end].decode(), ptype))
        pos = end + 1 + 16
    return out


def _unzip(data, expect):
    """zlib, then undo EXR's predictor (t[i] += t[i-1] - 128) and its
    interleaving of the two byte halves."""
    raw = np.frombuffer(zlib.decompress(data), dtype=np.uint8).astype(np.int64)
    raw[1:] -= 128
    t = (np.cumsum(raw) & 0xFF).astype(np.uint8)
    half = (len(t) + 1) // 2
    out = np.empty(len(t), dtype=np.uint8)
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    if len(out) != expect:
        raise ValueError(f"EXR chunk: {len(out)} bytes, expected {expect}")
    return out.tobytes()


def read(path):
    """{channel name: 2D float array (row 0 at the top)} of an EXR file."""
    with open(path, "rb") as fp:
        buf = fp.read()
    if buf[:4] != b"\x76\x2f\x31\x01":
        raise ValueError(f"{path}: not an EXR file")
    attrs, pos = _attrs(buf)
    chans = sorted(_channels(attrs["channels"][1]))
    comp = attrs["compression"][1][0]
    if comp not in _LINES:
        raise ValueError(f"{path}: compression {comp} not supported")
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"][1])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    lines = _LINES[comp]
    nchunks = (h + lines - 1) // lines
    offsets = struct.unpack_from(f"<{nchunks}Q", buf, pos)
    out = {n: np.empty((h, w), dtype=np.float64) for n, _ in chans}
    for off in offsets:
        y, size = struct.unpack_from("<ii", buf, off)
        data = buf[off + 8:off + 8 + size]
        nl = min(lines, y1 - y + 1)
        expect = nl * w * sum(_TYPES[t][1] for _, t in chans)
        if comp != 0 and size < expect:
            data = _unzip(data, expect)
        p = 0
        for r in range(nl):
            for name, t in chans:
                dt, sz = _TYPES[t]
                out[name][y - y0 + r] = np.frombuffer(data, dtype=dt, count=w, offset=p)
                p += sz * w
    return out
