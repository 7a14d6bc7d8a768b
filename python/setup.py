"""setup.py: builds the icshadow package over the project's C libraries.

The libraries come from the CMake build tree that `make` leaves in build/ (ICSHADOW_BUILD_DIR
names another); when it has none, this builds them there first (cmake, Release). The two
shared libraries are copied into the package, so the installed package works after the build
tree is gone.
"""
import os
import shutil
import subprocess
import sys

from setuptools import setup
from setuptools.command.build_ext import build_ext

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from icshadow_build import BUILD_DIR, LIB_DIR, REPO  # noqa: E402

SONAMES = ["libicshadow.so.0", "libicshadow_render.so.0"]


def ensure_libraries():
    if all(os.path.exists(os.path.join(LIB_DIR, s)) for s in SONAMES):
        return
    print(f"icshadow: no C libraries in {LIB_DIR}: building them (cmake, Release)")
    subprocess.check_call(["cmake", "-S", REPO, "-B", BUILD_DIR, "-DCMAKE_BUILD_TYPE=Release"])
    subprocess.check_call(["cmake", "--build", BUILD_DIR, "-j", str(os.cpu_count() or 2),
                           "--target", "icshadow_shared", "icshadow_render_shared"])


class BuildWithLibraries(build_ext):
    def run(self):
        ensure_libraries()
        dests = [os.path.join(self.build_lib, "icshadow")]
        if self.inplace:
            dests.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "icshadow"))
        for d in dests:
            os.makedirs(d, exist_ok=True)
            for s in SONAMES:  # the real file under its soname, which the module's rpath finds
                shutil.copy2(os.path.realpath(os.path.join(LIB_DIR, s)), os.path.join(d, s))
        self.force = True  # the headers' struct layouts are compiled in: never reuse a stale build
        super().run()


setup(
    cffi_modules=["icshadow_build.py:ffibuilder"],
    cmdclass={"build_ext": BuildWithLibraries},
)
