"""lut.py: the lookup tables of ratioToab and abToVarx (docs/lut.md) as arrays, and the headers
`icshadow lut` writes, as text."""
import numpy as np

from ._lib import Error, check, ffi, lib, msg_buffer, take_string

LANGS = ("c", "glsl", "opencl", "c-data")  # the order of ics_lut_lang


def lut(n=256):
    """The n-entry tables (s, g) built from the exact functions: s(w) = t / w at
    w_i = i / (2 (n - 1)) and g(t) = V_x(t) / (1 - t)^2 (docs/lut.md), as float64 arrays."""
    n = int(n)
    size = n if lib.ICS_LUT_MIN_SIZE <= n <= lib.ICS_LUT_MAX_SIZE else 1  # else refused below
    s, g = np.zeros(size), np.zeros(size)
    check(lib.ics_lut_build(n, ffi.from_buffer("double[]", s), ffi.from_buffer("double[]", g)),
          context=f"lut: size {n}: ")
    return s, g


def lut_header(n=256, lang="c"):
    """The header `icshadow lut --size n --lang lang` writes (c, glsl, opencl or c-data), stamped
    with that command and the error measured on the stamp grid: the same text."""
    if lang not in LANGS:
        raise ValueError(f"lut_header: lang: unknown value {lang!r} (expected {', '.join(LANGS)})")
    n = int(n)
    msg = msg_buffer()
    command = f"icshadow lut --size {n} --lang {lang}".encode()
    p = lib.icspy_lut_header(n, LANGS.index(lang), command, msg, len(msg))
    if p == ffi.NULL:
        text = ffi.string(msg).decode()
        if text == "out of memory":
            raise MemoryError(f"lut_header: size {n}: {text}")
        raise Error(f"lut_header: size {n}: {text}", text)
    return take_string(p, "lut_header")
