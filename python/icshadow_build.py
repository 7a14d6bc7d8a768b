"""icshadow_build.py: the cffi builder of icshadow._ffi (API mode, out of line).

It compiles icshadow/_binding.c against the project's headers and links it with
libicshadow_render and libicshadow from the C build (LIB_DIR below), with an rpath of
$ORIGIN: setup.py copies those two libraries into the package beside the module.
"""
import os

from cffi import FFI

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
# the CMake build tree whose lib/ holds the shared libraries (make: build/)
BUILD_DIR = os.path.abspath(os.environ.get("ICSHADOW_BUILD_DIR", os.path.join(REPO, "build")))
LIB_DIR = os.path.join(BUILD_DIR, "lib")


def _read(name):
    with open(os.path.join(HERE, "icshadow", name), encoding="utf-8") as f:
        return f.read()


ffibuilder = FFI()
ffibuilder.cdef(_read("_binding.h"))
ffibuilder.set_source(
    "icshadow._ffi",
    _read("_binding.c"),
    include_dirs=[os.path.join(REPO, "libicshadow", "include"), os.path.join(REPO, "gpu", "include")],
    library_dirs=[LIB_DIR],
    libraries=["icshadow_render", "icshadow"],
    extra_compile_args=["-std=c11", "-Wall"],
    extra_link_args=["-Wl,-rpath,$ORIGIN"],
)

if __name__ == "__main__":
    ffibuilder.compile(verbose=True)
