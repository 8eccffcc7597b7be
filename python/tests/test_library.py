"""The package's C library: bundled, version, FC3D_LIBRARY override."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import fc3d

CHECK = "import fc3d; print(fc3d.library_path); print(fc3d.__version__)"


def run_python(code, **env):
    """Runs ``code`` in a fresh interpreter with ``env`` added (FC3D_LIBRARY unset unless given)."""
    environment = dict(os.environ)
    environment.pop("FC3D_LIBRARY", None)
    environment.update(env)
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=environment, timeout=60)


def test_version():
    """__version__ is the library's semantic version."""
    assert re.fullmatch(r"\d+\.\d+\.\d+([-+.].*)?", fc3d.__version__)


def test_library_is_bundled():
    """Without FC3D_LIBRARY the package loads the copy installed inside it."""
    out = run_python(CHECK)
    assert out.returncode == 0, out.stderr
    path = Path(out.stdout.splitlines()[0])
    assert path.parent == Path(fc3d.__file__).parent, path
    assert out.stdout.splitlines()[1] == fc3d.__version__


def test_fc3d_library_override(tmp_path):
    """FC3D_LIBRARY=path loads that file."""
    copy = tmp_path / "libcopy.so"
    shutil.copyfile(fc3d.library_path, copy)
    out = run_python(CHECK, FC3D_LIBRARY=str(copy))
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines()[0] == str(copy)


def test_fc3d_library_override_missing(tmp_path):
    """FC3D_LIBRARY naming a missing file is an ImportError naming it."""
    missing = tmp_path / "nothing.so"
    out = run_python(CHECK, FC3D_LIBRARY=str(missing))
    assert out.returncode != 0
    assert "ImportError" in out.stderr and "FC3D_LIBRARY=%s" % missing in out.stderr


def test_fc3d_library_override_wrong_library(tmp_path):
    """A library without the native entry is refused with the missing names."""
    libm = None
    for candidate in ("/lib/x86_64-linux-gnu/libm.so.6", "/usr/lib/x86_64-linux-gnu/libm.so.6",
                      "/lib64/libm.so.6", "/usr/lib/libm.so.6"):
        if os.path.exists(candidate):
            libm = candidate
            break
    if libm is None:
        import pytest

        pytest.skip("no libm found to load")
    out = run_python(CHECK, FC3D_LIBRARY=libm)
    assert out.returncode != 0 and "does not export fc3d's native entry" in out.stderr
