"""exr.py: images in files through the C libraries: OpenEXR read and written channel by channel
(R, G, B, A, light0.V, Z, stderr.R, ... as the renderer writes them), and 8-bit sRGB PNG previews.
Both are written whole or not at all (a temporary file beside the target, renamed)."""
import json
import os

import numpy as np

from ._lib import check, ffi, image_from_array, lib, msg_buffer, real_array, write_replacing


def channels_to_dict(ch):
    """An ics_exr_channels' channels as {name: (height, width) float32 array}, row 0 at the top."""
    data = np.frombuffer(ffi.buffer(ch.data, 4 * ch.width * ch.height * ch.count), np.float32)
    data = data.reshape(ch.height, ch.width, ch.count)
    return {ffi.string(ch.names[c]).decode(errors="replace"): data[:, :, c].copy()
            for c in range(ch.count)}


def read_exr(path):
    """(channels, info): every channel of the EXR at path as {name: (height, width) float32},
    and its "icshadow" attribute (the render summary of a render the CLI wrote, parsed as a
    dict; None when absent)."""
    out, msg = ffi.new("ics_exr_channels **"), msg_buffer()
    check(lib.ics_exr_read_channels(os.fsencode(path), out, msg, len(msg)), msg)
    ch = ffi.gc(out[0], lib.ics_exr_channels_destroy)
    info = ffi.string(ch.info).decode(errors="replace") if ch.info != ffi.NULL else None
    try:
        info = json.loads(info) if info else None
    except ValueError:
        pass  # another writer's text: kept as it is
    return channels_to_dict(ch), info


def write_exr(path, channels, info=None):
    """Writes {name: (height, width) array} as a float EXR, channels in the dict's order; info (a
    dict or a text, may be None) goes into its "icshadow" attribute, where `read_exr` and
    `icshadow render --compare` find a render's summary."""
    names = list(channels)
    if not names:
        raise ValueError("write_exr: no channels")
    if any("\0" in n or not n for n in names):
        raise ValueError("write_exr: a channel name is empty or holds a NUL")
    planes = [real_array(channels[n], f"write_exr: {n}", np.float32) for n in names]
    shape = planes[0].shape
    if len(shape) != 2 or any(p.shape != shape for p in planes):
        raise ValueError(f"write_exr: every channel must be one (height, width) array; got "
                         f"{', '.join(f'{n} {p.shape}' for n, p in zip(names, planes))}")
    data = np.ascontiguousarray(np.stack(planes, axis=-1))
    cnames = [ffi.new("char[]", n.encode()) for n in names]
    ctext = ffi.new("char[]", (info if isinstance(info, str) else json.dumps(info)).encode()) \
        if info is not None else ffi.NULL
    ch = ffi.new("ics_exr_channels *")
    ch.height, ch.width, ch.count = shape[0], shape[1], len(names)
    name_arr = ffi.new("const char *[]", cnames)
    cdata = ffi.from_buffer("float[]", data)  # kept alive with data for the call
    ch.names, ch.data, ch.info = name_arr, cdata, ctext
    msg = msg_buffer()
    check(lib.ics_exr_write_channels(os.fsencode(path), ch, lib.ICS_EXR_FLOAT, 0, msg, len(msg)), msg)


def srgb(linear):
    """The sRGB encoding (IEC 61966-2-1) of linear values in [0, 1], as the PNG previews are
    encoded: for showing a render (clip it to [0, 1] first)."""
    from .numerics import map_function
    return map_function("ics_output_srgb", linear, "srgb")


def write_png(path, rgb):
    """Writes an image (height, width, 3 or 4) of linear values as an 8-bit sRGB PNG preview
    (clamped to [0, 1]; alpha is not written), as `icshadow render --png` does."""
    img = image_from_array(rgb, "write_png")

    def write(tmp):
        msg = msg_buffer()
        check(lib.ics_output_png(img, os.fsencode(tmp), msg, len(msg)), msg)

    write_replacing(path, "write_png", write)
