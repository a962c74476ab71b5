"""`pip install .`: builds the Python module lamina with CMake and packs it.

    /usr/bin/python3 -m venv --system-site-packages .venv
    .venv/bin/pip install --no-build-isolation .

build_ext configures the project (Release, -DLAMINA_BUILD_TESTS=OFF,
-DLAMINA_PYTHON=ON, -DPython_EXECUTABLE=<the installing interpreter>, then
the words of $CMAKE_ARGS) in build-pip/, builds the target lamina_python
($CMAKE_BUILD_PARALLEL_LEVEL jobs, else one per core) and copies the package
it lays out in <build>/python/lamina (the extension _lamina, the .py and .pyi
files, py.typed) into the wheel, with materials/catalog.toml as
lamina/catalog.toml (the catalog of an installed package whose source tree
is gone: python/lamina/__init__.py).

$LAMINA_BUILD_DIR names a build folder to use instead: a configured one is
reused as it is (its options, its source tree; only lamina_python is
built, so after `make build` this takes seconds); an empty or missing one
is configured as above. Its extension must be for the installing
interpreter (the same EXT_SUFFIX), else the install stops and says so.
"""
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def version():
    """The project's version: CMakeLists.txt's project(lamina VERSION x.y.z)."""
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(lamina VERSION ([0-9.]+)", text).group(1)


def cached(build, name):
    """The value of the cache entry @name (NAME:TYPE=value) in build's CMakeCache.txt, or None."""
    for line in (build / "CMakeCache.txt").read_text().splitlines():
        if line.startswith(name + ":"):
            return line.split("=", 1)[1]
    return None


class CMakeBuild(build_ext):
    """build_ext over CMake (the module's docstring)."""

    def run_command_line(self, args):
        print("lamina setup.py: " + " ".join(shlex.quote(str(a)) for a in args), flush=True)
        subprocess.run([str(a) for a in args], check=True)

    def configure(self, build):
        args = ["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                "-DLAMINA_BUILD_TESTS=OFF", "-DLAMINA_PYTHON=ON",
                "-DPython_EXECUTABLE=" + sys.executable]
        self.run_command_line(args + shlex.split(os.environ.get("CMAKE_ARGS", "")))

    def build_extension(self, ext):
        named = os.environ.get("LAMINA_BUILD_DIR")
        build = pathlib.Path(named).resolve() if named else pathlib.Path(self.build_temp,
                                                                          "cmake").resolve()
        if not (build / "CMakeCache.txt").exists():
            self.configure(build)
        elif named:
            source = cached(build, "CMAKE_HOME_DIRECTORY")
            print(f"lamina setup.py: reusing the build folder {build} (sources: {source})",
                  flush=True)
        jobs = [] if os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") else ["-j", os.cpu_count() or 1]
        try:
            self.run_command_line(["cmake", "--build", build, "--target", "lamina_python", *jobs])
        except subprocess.CalledProcessError as e:
            sys.exit(f"lamina setup.py: building lamina_python in {build} failed ({e}); if the "
                     "target is unknown, CMake found no pybind11 or Python headers (Debian: "
                     "pybind11-dev python3-dev, scripts/install-deps.sh) or LAMINA_PYTHON is OFF")
        self.pack(build / "python" / "lamina", pathlib.Path(self.get_ext_fullpath(ext.name)))

    def pack(self, built, extension):
        """Copies the package built in @built into the wheel's tree (the
        folder of @extension, the path setuptools expects the extension at)."""
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        found = sorted(p.name for p in built.glob("_lamina*.so"))
        if "_lamina" + suffix not in found:
            sys.exit(f"lamina setup.py: {built} has no _lamina{suffix} for {sys.executable} "
                     f"(found: {', '.join(found) or 'none'}); name another build folder in "
                     "LAMINA_BUILD_DIR, or none")
        target = extension.parent
        target.mkdir(parents=True, exist_ok=True)
        for path in built.iterdir():
            if path.is_file() and (path.suffix in (".py", ".pyi") or path.name == "py.typed"):
                shutil.copy2(path, target / path.name)
        shutil.copy2(built / ("_lamina" + suffix), extension)
        shutil.copy2(ROOT / "materials" / "catalog.toml", target / "catalog.toml")


setup(
    version=version(),
    packages=[],
    py_modules=[],
    ext_modules=[Extension("lamina._lamina", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-pip"}},
    zip_safe=False,
)
