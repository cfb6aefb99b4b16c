"""Builds vorball._core against libvorball.

libvorball is the C library of the repository around this folder: this
script brings its CMake build up to date (VORBALL_BUILD_DIR, default
../build, configured as a Release build when it does not exist), installs
the libvorball component (headers, shared library) into a staging prefix,
compiles the extension against it and puts libvorball.so.N beside the
extension, which finds it through its rpath ($ORIGIN). So `pip install
./python` works from a checkout after the README's set-up, and the
installed package needs nothing from the checkout afterwards.
"""
import glob
import os
import re
import shutil
import subprocess

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def project_version():
    """The version of the C library (project() in ../CMakeLists.txt)."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        m = re.search(r"project\(vorball\s+VERSION\s+([0-9.]+)", f.read())
    if not m:
        raise SystemExit("setup.py: no project(vorball VERSION ...) in ../CMakeLists.txt")
    return m.group(1)


class BuildWithLibvorball(build_ext):
    def run(self):
        if not os.path.exists(os.path.join(ROOT, "core", "vb.h")):
            raise SystemExit("setup.py builds libvorball from the vorball checkout around "
                             "python/: run `pip install ./python` in a checkout")
        build = os.environ.get("VORBALL_BUILD_DIR") or os.path.join(ROOT, "build")
        build = os.path.abspath(build)
        jobs = str(os.cpu_count() or 2)
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            subprocess.check_call(["cmake", "-S", ROOT, "-B", build,
                                   "-DCMAKE_BUILD_TYPE=Release"])
        subprocess.check_call(["cmake", "--build", build, "--target", "libvorball", "-j", jobs])
        stage = os.path.abspath(os.path.join(self.build_temp, "libvorball"))
        shutil.rmtree(stage, ignore_errors=True)
        subprocess.check_call(["cmake", "--install", build, "--prefix", stage,
                               "--component", "libvorball"])
        libs = glob.glob(os.path.join(stage, "lib*", "**", "libvorball.so"), recursive=True)
        if not libs:
            raise SystemExit("setup.py: cmake --install gave no libvorball.so in " + stage)
        libdir = os.path.dirname(libs[0])
        headers = glob.glob(os.path.join(stage, "include", "vorball", "*.h"))
        for ext in self.extensions:
            ext.include_dirs.append(os.path.join(stage, "include", "vorball"))
            ext.library_dirs.append(libdir)
            # The library's headers and the library itself: an extension
            # left in build/ by an earlier install is rebuilt when either
            # is newer (a struct of the library changed, or its code).
            ext.depends = list(ext.depends) + headers + [os.path.realpath(libs[0])]
        super().run()
        # The loader looks for the soname (libvorball.so.0): copy the file
        # under that name beside the extension.
        real = os.path.realpath(libs[0])
        soname = re.sub(r"(\.so\.[0-9]+)\..*$", r"\1", os.path.basename(real))
        dest = os.path.dirname(self.get_ext_fullpath("vorball._core"))
        os.makedirs(dest, exist_ok=True)
        shutil.copyfile(real, os.path.join(dest, soname))


flags = ["-std=c11", "-Wall", "-Wextra", "-ffp-contract=off"]
if os.environ.get("VORBALL_WERROR") == "1":
    flags.append("-Werror")

setup(
    version=project_version(),
    ext_modules=[Extension(
        "vorball._core",
        sources=sorted(glob.glob(os.path.join("src", "*.c"))),
        depends=glob.glob(os.path.join("src", "*.h")),
        libraries=["vorball"],
        extra_compile_args=flags,
        extra_link_args=["-Wl,-rpath,$ORIGIN"],
    )],
    cmdclass={"build_ext": BuildWithLibvorball},
)
