"""_lib.py: the compiled binding (icshadow._ffi) and how its errors become exceptions."""
import os
import tempfile

import numpy as np

from ._ffi import ffi, lib

MSG_SIZE = 2048  # bytes of a library message buffer


class Error(RuntimeError):
    """An error the C library reported: str(e) is its message; e.status the status text
    ("cannot parse input", "argument out of range", ...), as the CLI would print them."""

    def __init__(self, message, status=""):
        super().__init__(message)
        self.status = status


def msg_buffer():
    return ffi.new("char[]", MSG_SIZE)


def check(st, msg=None, context=""):
    """Raises Error for a status other than ICS_OK with the library's message (MemoryError for
    ICS_ERR_NOMEM)."""
    if st == lib.ICS_OK:
        return
    status = ffi.string(lib.ics_status_str(st)).decode()
    text = ffi.string(msg).decode(errors="replace") if msg is not None else ""
    text = text or status
    if st == lib.ICS_ERR_NOMEM:
        raise MemoryError(f"{context}{text}")
    raise Error(f"{context}{text}", status)


def take_string(p, what):
    """A string a helper malloc'ed (freed here); NULL is out of memory."""
    if p == ffi.NULL:
        raise MemoryError(f"{what}: out of memory")
    try:
        return ffi.string(p).decode()
    finally:
        lib.icspy_free(p)


def real_array(x, name, dtype=np.float64):
    """x as a C-contiguous array of dtype, its shape kept; TypeError for anything that is not
    real numbers (complex, strings, objects, booleans)."""
    a = np.asarray(x)
    if a.dtype.kind not in "iuf":
        raise TypeError(f"{name}: expected real numbers, got an array of {a.dtype}")
    return np.require(a, dtype=dtype, requirements="C")


def write_replacing(path, what, write):
    """Writes a file whole or not at all: write(tmp) fills a temporary file beside path, which is
    then renamed over it, with the mode a new file gets (0666 less the umask; mkstemp's is
    0600)."""
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise FileNotFoundError(f"{what}: {path}: the folder {folder} does not exist")
    fd, tmp = tempfile.mkstemp(prefix=".icshadow.", dir=folder)
    os.close(fd)
    try:
        write(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def image_from_array(arr, name, channels=(3, 4)):
    """A new ics_image (freed when collected) holding arr, shape (height, width, C), row 0 at
    the top; ValueError for another shape or a NaN or infinite value."""
    a = real_array(arr, name, np.float32)
    if a.ndim != 3 or a.shape[2] not in channels:
        raise ValueError(f"{name}: expected shape (height, width, {' or '.join(map(str, channels))}),"
                         f" got {a.shape}")
    if not np.isfinite(a).all():
        raise ValueError(f"{name}: has a NaN or infinite value")
    h, w, c = a.shape
    out = ffi.new("ics_image **")
    check(lib.ics_image_create(out, w, h, c), context=f"{name}: {w}x{h}: ")
    img = ffi.gc(out[0], lib.ics_image_destroy)
    np.frombuffer(ffi.buffer(img.data, a.nbytes), dtype=np.float32)[:] = a.reshape(-1)
    return img


def image_to_array(img):
    """An ics_image's pixels as a new float32 array (height, width, channels)."""
    n = img.width * img.height * img.channels
    flat = np.frombuffer(ffi.buffer(img.data, 4 * n), dtype=np.float32)
    return flat.reshape(img.height, img.width, img.channels).copy()
