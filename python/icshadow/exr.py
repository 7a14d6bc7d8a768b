"""exr.py: OpenEXR images read through libicshadow (OpenEXR's C API): every channel by name, as
the renderer writes them (R, G, B, A, light0.V, Z, stderr.R, ...)."""
import os

import numpy as np

from ._lib import check, ffi, lib, msg_buffer


def channels_to_dict(ch):
    """An ics_exr_channels' channels as {name: (height, width) float32 array}, row 0 at the top."""
    data = np.frombuffer(ffi.buffer(ch.data, 4 * ch.width * ch.height * ch.count), np.float32)
    data = data.reshape(ch.height, ch.width, ch.count)
    return {ffi.string(ch.names[c]).decode(): data[:, :, c].copy() for c in range(ch.count)}


def read_exr(path):
    """(channels, info): every channel of the EXR at path as {name: (height, width) float32},
    and its "icshadow" attribute (the render summary of a render the CLI wrote, parsed as a
    dict; None when absent)."""
    import json

    out, msg = ffi.new("ics_exr_channels **"), msg_buffer()
    check(lib.ics_exr_read_channels(os.fsencode(path), out, msg, len(msg)), msg)
    ch = ffi.gc(out[0], lib.ics_exr_channels_destroy)
    info = ffi.string(ch.info).decode() if ch.info != ffi.NULL else None
    try:
        info = json.loads(info) if info else None
    except ValueError:
        pass  # another writer's text: kept as it is
    return channels_to_dict(ch), info
