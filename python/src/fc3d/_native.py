"""Loading of fc3d's native C library and the ctypes prototypes of its native entry.

The library is, in this order:

1. the file named by the environment variable ``FC3D_LIBRARY`` (read at import; when set, it is
   the only candidate, and a failure to load it is an ImportError);
2. the copy bundled in the package at build time (``fc3d/libfc3d_native.so``);
3. a system installation found by ``ctypes.util.find_library("fc3d_native")`` (e.g. installed by
   ``scripts/install.sh``).

Either build of the Rust crate works: the native-only ``libfc3d_native`` or the drop-in
``libfc3d`` (both export the native entry).
"""

import ctypes
import ctypes.util
import os
import sys
from ctypes import POINTER, c_char_p, c_double, c_int, c_int64, c_void_p

from ._errors import Fc3dError

ENV_LIBRARY = "FC3D_LIBRARY"

_HERE = os.path.dirname(os.path.abspath(__file__))

if sys.platform == "win32":  # pragma: no cover
    _BUNDLED = "fc3d_native.dll"
elif sys.platform == "darwin":  # pragma: no cover
    _BUNDLED = "libfc3d_native.dylib"
else:
    _BUNDLED = "libfc3d_native.so"


class Fc3dResult(ctypes.Structure):
    """``struct Fc3dResult`` of fc3d_native.h."""

    _fields_ = [
        ("info", c_int),
        ("iterations", c_int64),
        ("error", c_double),
        ("seconds", c_double),
    ]


_dp = POINTER(c_double)
_ip = POINTER(c_int64)

# name: (restype, argtypes), exactly as declared in capi/include/fc3d_native.h.
_PROTOTYPES = {
    "fc3d_last_error_message": (c_char_p, []),
    "fc3d_last_error_code": (c_int, []),
    "fc3d_clear_last_error": (None, []),
    "fc3d_version": (c_char_p, []),
    "fc3d_settings_new": (c_void_p, [c_int]),
    "fc3d_settings_free": (None, [c_void_p]),
    "fc3d_settings_set_tolerance": (c_int, [c_void_p, c_double]),
    "fc3d_settings_set_max_iter": (c_int, [c_void_p, c_int64]),
    "fc3d_settings_set_time_budget": (c_int, [c_void_p, c_double]),
    "fc3d_settings_set_local_solver": (c_int, [c_void_p, c_int]),
    "fc3d_settings_set_iparam": (c_int, [c_void_p, c_int, c_int]),
    "fc3d_settings_set_dparam": (c_int, [c_void_p, c_int, c_double]),
    "fc3d_settings_set_local_iparam": (c_int, [c_void_p, c_int, c_int]),
    "fc3d_settings_set_local_dparam": (c_int, [c_void_p, c_int, c_double]),
    "fc3d_settings_set": (c_int, [c_void_p, c_char_p, c_double]),
    "fc3d_solve_dense": (
        c_int,
        [c_int64, _dp, _dp, _dp, _dp, _dp, c_void_p, POINTER(Fc3dResult)],
    ),
    "fc3d_solve_csr": (
        c_int,
        [c_int64, c_int64, _ip, _ip, _dp, _dp, _dp, _dp, _dp, c_void_p, POINTER(Fc3dResult)],
    ),
    "fc3d_solve_coo": (
        c_int,
        [c_int64, c_int64, _ip, _ip, _dp, _dp, _dp, _dp, _dp, c_void_p, POINTER(Fc3dResult)],
    ),
    "fc3d_solve_blocks": (
        c_int,
        [c_int64, c_int64, _ip, _ip, _dp, _dp, _dp, _dp, _dp, c_void_p, POINTER(Fc3dResult)],
    ),
    "fc3d_solve_global_csr": (
        c_int,
        [c_int64, c_int64, c_int64, _ip, _ip, _dp, c_int64, _ip, _ip, _dp, _dp, _dp, _dp,
         _dp, _dp, _dp, c_void_p, POINTER(Fc3dResult)],
    ),
    "fc3d_solve_global_coo": (
        c_int,
        [c_int64, c_int64, c_int64, _ip, _ip, _dp, c_int64, _ip, _ip, _dp, _dp, _dp, _dp,
         _dp, _dp, _dp, c_void_p, POINTER(Fc3dResult)],
    ),
    "fc3d_solve_global_blocks": (
        c_int,
        [c_int64, c_int64, _dp, c_int64, c_int64, _ip, _ip, _dp, _dp, _dp, _dp, _dp, _dp, _dp,
         c_void_p, POINTER(Fc3dResult)],
    ),
    "fc3d_problem_read": (c_void_p, [c_char_p]),
    "fc3d_problem_free": (None, [c_void_p]),
    "fc3d_problem_contacts": (c_int64, [c_void_p]),
    "fc3d_problem_nnz": (c_int64, [c_void_p]),
    "fc3d_problem_get": (c_int, [c_void_p, _ip, _ip, _dp, _dp, _dp]),
    "fc3d_problem_solve": (c_int, [c_void_p, _dp, _dp, c_void_p, POINTER(Fc3dResult)]),
    "fc3d_solver_count": (c_int, []),
    "fc3d_solver_at": (c_int, [c_int, POINTER(c_char_p), POINTER(c_char_p)]),
}


def _candidates():
    """The library files to try, in order, with where each comes from."""
    override = os.environ.get(ENV_LIBRARY)
    if override:
        return [(override, "%s=%s" % (ENV_LIBRARY, override))], True
    found = []
    bundled = os.path.join(_HERE, _BUNDLED)
    if os.path.exists(bundled):
        found.append((bundled, "the library bundled in the package"))
    system = ctypes.util.find_library("fc3d_native")
    if system:
        found.append((system, "the system library %s" % system))
    return found, False


def _load():
    """Loads the first candidate library exporting the native entry; ImportError otherwise."""
    candidates, overridden = _candidates()
    if not candidates:
        raise ImportError(
            "fc3d: the C library was not found: %s is missing (reinstall the package with "
            "`pip install ./python` from the fc3d repository, which builds it with cargo), and no "
            "libfc3d_native is installed on the system; or set %s=/path/to/libfc3d_native.so"
            % (os.path.join(_HERE, _BUNDLED), ENV_LIBRARY)
        )
    errors = []
    for path, origin in candidates:
        try:
            lib = ctypes.CDLL(path)
        except OSError as e:
            errors.append("%s: %s" % (origin, e))
            continue
        missing = [name for name in _PROTOTYPES if not hasattr(lib, name)]
        if missing:
            errors.append(
                "%s does not export fc3d's native entry (missing %s): is it an older fc3d?"
                % (origin, ", ".join(missing))
            )
            continue
        for name, (restype, argtypes) in _PROTOTYPES.items():
            function = getattr(lib, name)
            function.restype = restype
            function.argtypes = argtypes
        return lib, path
    hint = "" if overridden else " (set %s=/path/to/libfc3d_native.so to choose one)" % ENV_LIBRARY
    raise ImportError("fc3d: cannot load the C library%s:\n  %s" % (hint, "\n  ".join(errors)))


lib, library_path = _load()


def last_error():
    """The Fc3dError of the last failed call of this thread (code and message of the library)."""
    message = lib.fc3d_last_error_message()
    code = lib.fc3d_last_error_code()
    text = message.decode("utf-8", "replace") if message else ""
    if not text:
        text = "fc3d call failed with code %d (no message)" % code
    return Fc3dError(text, code if code < 0 else -99)


def check(code):
    """Raises the library's last error when ``code`` is negative; returns ``code`` otherwise."""
    if code < 0:
        error = last_error()
        if error.code != code:
            # A mismatch would be a bug of the C entry; keep the code the call returned.
            error = Fc3dError(error.message, code)
        raise error
    return code


def version():
    """The library's version string (``fc3d_version()``), e.g. ``"0.2.0"``."""
    return lib.fc3d_version().decode("ascii")


def solvers():
    """The solvers of the native entry, as the library lists them (``fc3d_solver_at``): a list of
    ``(id, constant, name)``, e.g. ``(500, "SICONOS_FRICTION_3D_NSGS", "FC3D_NSGS")``."""
    listed = []
    for index in range(lib.fc3d_solver_count()):
        constant, name = c_char_p(), c_char_p()
        solver = check(lib.fc3d_solver_at(index, ctypes.byref(constant), ctypes.byref(name)))
        listed.append((solver, constant.value.decode("ascii"), name.value.decode("ascii")))
    return listed


def double_ptr(array):
    """A ``double*`` to the data of a C-contiguous float64 numpy array."""
    return array.ctypes.data_as(_dp)


def int64_ptr(array):
    """An ``int64_t*`` to the data of a C-contiguous int64 numpy array."""
    return array.ctypes.data_as(_ip)
