"""setup.py: builds the icshadow package over the project's C libraries.

The libraries come from the CMake build tree that `make` leaves in build/ (ICSHADOW_BUILD_DIR
names another), brought up to date first (`cmake --build` of the two library targets; where
there is no build tree, one is configured, Release). The two
shared libraries are copied into the package, and the renderer's modules (the gl and cl
backends, Embree's and Assimp's readers: icshadow-NAME.so, loaded on first use) into its
icshadow/ folder, where the renderer looks beside itself, so the installed package works after
the build tree is gone.
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
    """The two libraries built from the sources as they are now (a no-op when they are up to
    date: the binding compiles the headers' struct layouts in, so a stale library must not be
    linked); a build tree is configured first where there is none."""
    if not os.path.exists(os.path.join(BUILD_DIR, "CMakeCache.txt")):
        print(f"icshadow: no CMake build in {BUILD_DIR}: configuring one (Release)")
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
            mods = os.path.join(LIB_DIR, "icshadow")  # the renderer's modules, beside it
            shutil.rmtree(os.path.join(d, "icshadow"), ignore_errors=True)  # none left from before
            os.makedirs(os.path.join(d, "icshadow"))
            for m in sorted(os.listdir(mods)) if os.path.isdir(mods) else []:
                if m.startswith("icshadow-") and m.endswith(".so"):
                    shutil.copy2(os.path.join(mods, m), os.path.join(d, "icshadow", m))
        self.force = True  # the headers' struct layouts are compiled in: never reuse a stale build
        super().run()


setup(
    cffi_modules=["icshadow_build.py:ffibuilder"],
    cmdclass={"build_ext": BuildWithLibraries},
)
