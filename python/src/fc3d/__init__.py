"""fc3d: solvers for the discrete 3D frictional contact problem FC(W, q, mu).

Find ``r, u`` in R^{3nc} with ``u = W r + q`` and, for every contact c (components ordered normal,
tangent 1, tangent 2), Signorini's condition and Coulomb's friction law of coefficient ``mu[c]``
(``K*_c ∋ (u_N + mu_c ||u_T||, u_T) ⟂ r_c ∈ K_c = { ||r_T|| <= mu_c r_N }``).

This package calls fc3d's C library (the native entry of ``fc3d_native.h``) through ctypes::

    >>> import numpy as np, fc3d
    >>> res = fc3d.solve(np.eye(3), [-1.0, 2.0, 0.0], [0.5], tol=1e-12)
    >>> res.r, res.u            # sliding: r = (1, -0.5, 0), u = (0, 1.5, 0)
    >>> p = fc3d.read_problem("Rover1039.dat")
    >>> fc3d.solve(p, solver="NSN_AC", tol=1e-8).error

Main names: :func:`solve` (solver ``"AUTO"`` by default), :func:`solve_global` (the global form:
M, H, q, b, mu; :data:`GLOBAL_SOLVERS`, :class:`GlobalResult`), :func:`read_problem`,
:class:`Problem`, :class:`Result`, :class:`Fc3dError`, :data:`SOLVERS` (every solver of the library by name, read
from the library at import), :data:`LOCAL_SOLVERS`, ``__version__`` (the C library's version).
The library is the one bundled at build time unless the environment variable ``FC3D_LIBRARY``
names another (read at import); :data:`library_path` tells which was loaded.
"""

from ._errors import (
    ERR_INTERNAL,
    ERR_INVALID_OPTION,
    ERR_INVALID_PROBLEM,
    ERR_INVALID_SIZE,
    ERR_INVALID_STORAGE,
    ERR_IO,
    ERR_NON_FINITE,
    ERR_NULL_POINTER,
    ERR_PARSE,
    ERR_UNSUPPORTED_SOLVER,
    NOT_CONVERGED,
    OK,
    RELAXED_NOT_COULOMB,
    TIME_BUDGET_EXHAUSTED,
    Fc3dError,
)
from ._native import library_path, version as _library_version
from ._solvers import LOCAL_SOLVERS, SOLVERS, local_solver_id, solver_id
from ._api import Problem, Result, read_problem, solve
from ._global import GLOBAL_SOLVERS, GlobalResult, global_solver_id, solve_global

#: The version of the loaded C library (``fc3d_version()``), e.g. ``"0.2.0"``.
__version__ = _library_version()

__all__ = [
    "solve",
    "solve_global",
    "read_problem",
    "Problem",
    "Result",
    "GlobalResult",
    "GLOBAL_SOLVERS",
    "global_solver_id",
    "Fc3dError",
    "SOLVERS",
    "LOCAL_SOLVERS",
    "solver_id",
    "local_solver_id",
    "library_path",
    "__version__",
    "OK",
    "NOT_CONVERGED",
    "TIME_BUDGET_EXHAUSTED",
    "RELAXED_NOT_COULOMB",
    "ERR_NULL_POINTER",
    "ERR_INVALID_SIZE",
    "ERR_INVALID_STORAGE",
    "ERR_NON_FINITE",
    "ERR_INVALID_OPTION",
    "ERR_UNSUPPORTED_SOLVER",
    "ERR_INVALID_PROBLEM",
    "ERR_PARSE",
    "ERR_IO",
    "ERR_INTERNAL",
]
