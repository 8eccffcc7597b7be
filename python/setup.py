"""Build of the fc3d Python package: runs cargo to build fc3d's native-only C library, bundles it.

The package is pure Python (ctypes) plus one shared library, ``libfc3d_native.so``, built from the
Rust workspace this directory lives in:

    cargo build --release -p fc3d --no-default-features --target-dir <repo>/target/native

(the same command and target directory as ``scripts/install.sh``, so either reuses the other's
build). The library is copied into the package (``fc3d/libfc3d_native.so``), which makes the
installed package self-contained. Environment variables read here, all optional:

``FC3D_SOURCE_DIR``
    The Rust workspace (default: the parent of this directory). Needed when building from an
    sdist unpacked elsewhere.
``FC3D_PREBUILT_LIBRARY``
    Bundle this already built ``libfc3d_native.so`` (or ``libfc3d.so``) instead of running cargo.
``FC3D_CARGO``
    The cargo command (default ``cargo``).
``FC3D_CARGO_TARGET_DIR``
    Cargo's target directory (default ``<repo>/target/native``).
``FC3D_CARGO_FEATURES``
    Extra cargo features, e.g. ``fclib`` to read FCLIB ``.hdf5`` files (needs libhdf5-dev).

The wheel is tagged ``py3-none-<platform>``: it holds a native library but no compiled Python
extension, so one wheel serves every CPython 3.8+ of the platform.
"""

import os
import re
import shutil
import subprocess
import sys

import setuptools
from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

try:  # setuptools >= 70.1 ships bdist_wheel; before, it came with the `wheel` package.
    from setuptools.command.bdist_wheel import bdist_wheel
except ImportError:  # pragma: no cover - depends on the build environment
    try:
        from wheel.bdist_wheel import bdist_wheel
    except ImportError:
        bdist_wheel = None

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = "fc3d"


def library_file_name():
    """File name of the shared library cargo builds for the `fc3d` crate on this platform."""
    if sys.platform == "win32":
        return "fc3d.dll"
    if sys.platform == "darwin":
        return "libfc3d.dylib"
    return "libfc3d.so"


def bundled_file_name():
    """File name of the library inside the package (what fc3d/_native.py loads)."""
    if sys.platform == "win32":
        return "fc3d_native.dll"
    if sys.platform == "darwin":
        return "libfc3d_native.dylib"
    return "libfc3d_native.so"


def source_dir():
    """The Rust workspace root, or None when this is not a source checkout (e.g. an sdist)."""
    root = os.environ.get("FC3D_SOURCE_DIR") or os.path.dirname(HERE)
    root = os.path.abspath(root)
    if os.path.isfile(os.path.join(root, "Cargo.toml")) and os.path.isdir(
        os.path.join(root, "capi")
    ):
        return root
    return None


def version():
    """The workspace version of Cargo.toml (the C library's version), or PKG-INFO's in an sdist."""
    root = source_dir()
    if root is not None:
        with open(os.path.join(root, "Cargo.toml"), encoding="utf-8") as f:
            text = f.read()
        m = re.search(
            r"^\[workspace\.package\][^\[]*?^version\s*=\s*\"([^\"]+)\"", text, re.M | re.S
        )
        if m:
            return m.group(1)
    pkg_info = os.path.join(HERE, "PKG-INFO")
    if os.path.isfile(pkg_info):
        with open(pkg_info, encoding="utf-8") as f:
            m = re.search(r"^Version:\s*(\S+)", f.read(), re.M)
        if m:
            return m.group(1)
    raise RuntimeError(
        "fc3d: cannot find the Rust workspace (Cargo.toml) above python/; "
        "set FC3D_SOURCE_DIR to the fc3d repository"
    )


def build_library(log):
    """Runs cargo (or takes FC3D_PREBUILT_LIBRARY) and returns the path of the built library."""
    prebuilt = os.environ.get("FC3D_PREBUILT_LIBRARY")
    if prebuilt:
        if not os.path.isfile(prebuilt):
            raise RuntimeError("fc3d: FC3D_PREBUILT_LIBRARY=%s is not a file" % prebuilt)
        log("fc3d: bundling the prebuilt library %s" % prebuilt)
        return prebuilt
    root = source_dir()
    if root is None:
        raise RuntimeError(
            "fc3d: no Rust workspace found to build the C library from. Build from the "
            "repository (pip install ./python), or set FC3D_SOURCE_DIR=/path/to/fc3d, or "
            "FC3D_PREBUILT_LIBRARY=/path/to/libfc3d_native.so"
        )
    cargo = os.environ.get("FC3D_CARGO", "cargo")
    if shutil.which(cargo) is None:
        raise RuntimeError(
            "fc3d: '%s' not found: building the fc3d Python package needs Rust's cargo "
            "(https://rustup.rs), or set FC3D_PREBUILT_LIBRARY=/path/to/libfc3d_native.so" % cargo
        )
    target_dir = os.path.abspath(
        os.environ.get("FC3D_CARGO_TARGET_DIR") or os.path.join(root, "target", "native")
    )
    command = [
        cargo, "build", "--release", "-p", "fc3d", "--no-default-features",
        "--target-dir", target_dir,
    ]
    features = os.environ.get("FC3D_CARGO_FEATURES", "").strip()
    if features:
        command += ["--features", features]
    log("fc3d: running %s (in %s)" % (" ".join(command), root))
    try:
        subprocess.run(command, cwd=root, check=True)
    except subprocess.CalledProcessError as e:
        raise RuntimeError(
            "fc3d: cargo failed (exit status %d): %s" % (e.returncode, " ".join(command))
        )
    built = os.path.join(target_dir, "release", library_file_name())
    if not os.path.isfile(built):
        raise RuntimeError("fc3d: cargo succeeded but %s is missing" % built)
    return built


class BuildPyWithLibrary(build_py):
    """build_py that also builds the C library and copies it into the package."""

    def run(self):
        """Builds the Python files, then the C library, and puts the library into the package."""
        if not getattr(self, "editable_mode", False):
            # The build folder is reused between builds: start the package afresh so that a
            # module removed from src/ is not shipped from an earlier build.
            shutil.rmtree(os.path.join(self.build_lib, PACKAGE), ignore_errors=True)
        super().run()
        library = build_library(lambda m: print(m, file=sys.stderr))
        if getattr(self, "editable_mode", False):
            # pip install -e: the package is imported from src/, so the library goes there.
            destination = os.path.join(HERE, "src", PACKAGE)
        else:
            destination = os.path.join(self.build_lib, PACKAGE)
        os.makedirs(destination, exist_ok=True)
        target = os.path.join(destination, bundled_file_name())
        # copy (not copy2) then chmod: an installed library must not keep cargo's timestamps
        # as a reason to be skipped, and must be readable by everyone.
        shutil.copyfile(library, target)
        os.chmod(target, 0o755)

    def get_outputs(self, include_bytecode=1):
        """The files build_py produces, the bundled library included (for the RECORD)."""
        outputs = super().get_outputs(include_bytecode)
        outputs.append(os.path.join(self.build_lib, PACKAGE, bundled_file_name()))
        return outputs


class BinaryDistribution(Distribution):
    """A distribution with a native library: installed in platlib, never tagged pure."""

    def has_ext_modules(self):
        """True: the package holds a native library (platlib, platform wheel)."""
        return True


cmdclass = {"build_py": BuildPyWithLibrary}

if bdist_wheel is not None:

    class BdistWheelPy3(bdist_wheel):
        """Tags the wheel py3-none-<platform>: ctypes needs no particular CPython ABI."""

        def finalize_options(self):
            """Marks the wheel as not pure (it holds a platform library)."""
            super().finalize_options()
            self.root_is_pure = False

        def get_tag(self):
            """The wheel tag: ``py3-none-<platform>``."""
            _, _, platform = super().get_tag()
            return "py3", "none", platform

    cmdclass["bdist_wheel"] = BdistWheelPy3

# project.license as a TOML table is deprecated by setuptools >= 77 (SPDX string), which older
# setuptools (the newest for Python 3.8 is 75) reject: give it here, in the form each understands.
_setuptools_major = int(re.match(r"\d+", setuptools.__version__).group(0))
_license = (
    {"license_expression": "Apache-2.0"} if _setuptools_major >= 77 else {"license": "Apache-2.0"}
)

# In a source checkout, setuptools' scratch folders go under the cargo target directory (ignored
# by git) rather than into python/.
_options = {}
if source_dir() is not None and not os.environ.get("FC3D_SOURCE_DIR"):
    _scratch = os.path.join(source_dir(), "target", "python")
    os.makedirs(_scratch, exist_ok=True)
    _options = {
        "build": {"build_base": os.path.join(_scratch, "build")},
        "egg_info": {"egg_base": _scratch},
    }

setup(
    version=version(),
    cmdclass=cmdclass,
    distclass=BinaryDistribution,
    options=_options,
    **_license,
)
