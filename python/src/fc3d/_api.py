"""The Python API: :func:`solve`, :func:`read_problem`, :class:`Problem`, :class:`Result`.

Everything numerical happens in the C library; this module converts numpy / scipy data to the
arrays the C entry takes (capi/include/fc3d_native.h) and back. The C functions take raw pointers,
so the sizes of the arrays are checked here before any call (Fc3dError with code
``ERR_INVALID_SIZE``); the values (NaN, negative mu, malformed sparse structures, option ranges)
are checked by the library, whose message the Fc3dError carries.
"""

import numbers
import os
import weakref
from collections.abc import Mapping

import numpy as np

from . import _native
from ._errors import (
    ERR_INVALID_OPTION,
    ERR_INVALID_SIZE,
    ERR_IO,
    ERR_NULL_POINTER,
    STATUS_NAMES,
    Fc3dError,
)
from ._native import Fc3dResult, check, double_ptr, int64_ptr, lib
from ._solvers import SOLVERS, local_solver_id, solver_id, solver_name

try:  # scipy is optional: sparse input and a sparse W from read_problem when available.
    import scipy.sparse as _sparse
except ImportError:  # pragma: no cover - exercised only without scipy
    _sparse = None

__all__ = ["Problem", "Result", "read_problem", "solve"]

_INDEXED_OPTIONS = ("iparam", "dparam", "local_iparam", "local_dparam")
_INT64_RANGE = (-(2 ** 63), 2 ** 63 - 1)


# ----------------------------------------------------------------------------------------------
# Results and problems.


class Result:
    """The outcome of :func:`solve`.

    Attributes:
        r: the reaction, a float64 array of length ``3 * n_contacts`` (per contact: normal,
            tangent 1, tangent 2).
        u: the velocity ``W r + q`` of the returned ``r``.
        info: 0 converged (``error <= tol``), 1 iteration limit reached, 2 time budget spent,
            3 (SOCLCP only) the relaxed problem is solved but ``r`` is not a Coulomb solution.
        error: the relative natural-map error of ``(r, u)`` (Siconos' normalisation).
        iterations: iterations done (sweeps, Newton steps, ... depending on the solver).
        seconds: wall-clock time of the solve in the library, seconds.
        solver: the Siconos id of the solver that ran.
    """

    __slots__ = ("r", "u", "info", "error", "iterations", "seconds", "solver")

    def __init__(self, r, u, info, error, iterations, seconds, solver):
        """Wraps the arrays and numbers of one solve."""
        self.r = r
        self.u = u
        self.info = int(info)
        self.error = float(error)
        self.iterations = int(iterations)
        self.seconds = float(seconds)
        self.solver = int(solver)

    @property
    def converged(self):
        """True when the solver reached the tolerance (``info == 0``)."""
        return self.info == 0

    @property
    def status(self):
        """``info`` as a word: ``converged``, ``max_iter``, ``time_budget`` or
        ``relaxed_not_coulomb``."""
        return STATUS_NAMES.get(self.info, str(self.info))

    @property
    def solver_name(self):
        """The solver's short name (``"NSGS"``, ``"NSN_AC"``, ...)."""
        return solver_name(self.solver)

    @property
    def n_contacts(self):
        """Number of contacts (``len(r) // 3``)."""
        return len(self.r) // 3

    def __repr__(self):
        """A one-line summary."""
        return "Result(%s, info=%d (%s), iterations=%d, error=%.3g, seconds=%.3g, nc=%d)" % (
            self.solver_name,
            self.info,
            self.status,
            self.iterations,
            self.error,
            self.seconds,
            self.n_contacts,
        )


class Problem:
    """A problem FC(W, q, mu) read from a file by :func:`read_problem`.

    Attributes:
        path: the file it was read from.
        n_contacts: number of contacts ``nc``.
        nnz: number of stored entries of W.
        W: the ``3nc x 3nc`` Delassus matrix: a ``scipy.sparse.csr_matrix`` when scipy is
            installed, else a dense numpy array.
        q: the free velocity, ``3nc`` values.
        mu: the friction coefficients, ``nc`` values.

    The arrays are read-only copies of the file's data (``W.copy()``, ``q.copy()`` give writable
    ones). ``solve(problem)`` (or ``problem.solve()``) solves the problem held by the library in
    the storage of its file (e.g. sparse 3x3 blocks); to solve a modified problem, pass arrays:
    ``fc3d.solve(W2, q2, mu2)``.
    """

    def __init__(self, handle, path):
        """Wraps the library's ``Fc3dProblem*`` (released when garbage-collected or by
        :meth:`close`) and copies its data out."""
        self._handle = handle
        self._finalizer = weakref.finalize(self, lib.fc3d_problem_free, handle)
        self.path = path
        self.n_contacts = int(lib.fc3d_problem_contacts(handle))
        self.nnz = int(lib.fc3d_problem_nnz(handle))
        n = 3 * self.n_contacts
        row_ptr = np.zeros(n + 1, dtype=np.int64)
        col_idx = np.zeros(self.nnz, dtype=np.int64)
        values = np.zeros(self.nnz, dtype=np.float64)
        q = np.zeros(n, dtype=np.float64)
        mu = np.zeros(self.n_contacts, dtype=np.float64)
        check(
            lib.fc3d_problem_get(
                handle, int64_ptr(row_ptr), int64_ptr(col_idx), double_ptr(values),
                double_ptr(q), double_ptr(mu),
            )
        )
        if _sparse is not None:
            W = _sparse.csr_matrix((values, col_idx, row_ptr), shape=(n, n))
            frozen = [W.data, W.indices, W.indptr, q, mu]
        else:
            W = np.zeros((n, n))
            rows = np.repeat(np.arange(n), np.diff(row_ptr))
            np.add.at(W, (rows, col_idx), values)
            frozen = [W, q, mu]
        for array in frozen:
            array.setflags(write=False)
        self.W, self.q, self.mu = W, q, mu

    @property
    def handle(self):
        """The library's ``Fc3dProblem*`` (an int); Fc3dError after :meth:`close`."""
        if not self._finalizer.alive:
            raise Fc3dError("fc3d: the problem %s was closed" % self.path, ERR_NULL_POINTER)
        return self._handle

    def close(self):
        """Releases the library's copy of the problem now (the arrays stay usable; solving the
        problem object then raises Fc3dError)."""
        self._finalizer()

    def __enter__(self):
        """Context manager: returns self."""
        return self

    def __exit__(self, *exc):
        """Context manager: releases the library's copy of the problem."""
        self.close()

    def solve(self, solver="AUTO", **kwargs):
        """Solves this problem: ``fc3d.solve(self, solver=solver, **kwargs)``, see :func:`solve`."""
        return solve(self, solver=solver, **kwargs)

    def __repr__(self):
        """A one-line summary."""
        return "Problem(%r, n_contacts=%d, nnz=%d)" % (self.path, self.n_contacts, self.nnz)


def read_problem(path):
    """Reads a Siconos ``.dat`` problem file (or an FCLIB ``.hdf5`` one when the library was built
    with the ``fclib`` feature) and returns a :class:`Problem` with ``W``, ``q``, ``mu`` and
    ``n_contacts``.

    Raises Fc3dError (code ``ERR_IO`` for an unreadable file, ``ERR_PARSE`` for a malformed one,
    ``ERR_INVALID_PROBLEM`` for a problem that is not 3D frictional contact) with the library's
    message.
    """
    path = os.fspath(path)
    encoded = os.fsencode(path)
    if b"\0" in encoded:
        raise Fc3dError("fc3d: read_problem: path %r contains a NUL character" % (path,), ERR_IO)
    handle = lib.fc3d_problem_read(encoded)
    if not handle:
        raise _native.last_error()
    return Problem(handle, path if isinstance(path, str) else os.fsdecode(path))


# ----------------------------------------------------------------------------------------------
# Input conversion.


def _size_error(message):
    """An Fc3dError with code ERR_INVALID_SIZE and a message in the library's style."""
    return Fc3dError("fc3d: solve: " + message, ERR_INVALID_SIZE)


def _real_array(x, what):
    """``x`` as a numpy array, refusing complex and object arrays (TypeError)."""
    array = np.asarray(x)
    if np.iscomplexobj(array):
        raise TypeError("%s must be real, got a complex array" % what)
    if array.dtype == object:
        raise TypeError("%s must be a numeric array, got %r" % (what, type(x).__name__))
    return array


def _vector(x, what, length):
    """A C-contiguous float64 copy-or-view of ``x``, checked to be 1-D of ``length``."""
    array = _real_array(x, what)
    if array.ndim != 1:
        raise _size_error("%s must be a 1-D array, got shape %s" % (what, array.shape))
    if length is not None and array.shape[0] != length:
        raise _size_error("%s has %d entries, %d expected" % (what, array.shape[0], length))
    return np.ascontiguousarray(array, dtype=np.float64)


def _is_sparse(W):
    """True when ``W`` is a scipy.sparse matrix or array."""
    if _sparse is not None:
        return _sparse.issparse(W)
    return hasattr(W, "tocsr") and hasattr(W, "format") and hasattr(W, "shape")


def _index_array(x):
    """``x`` as a C-contiguous int64 array (the C entry's index type)."""
    return np.ascontiguousarray(x, dtype=np.int64)


def _prepare_matrix(W, n):
    """Returns a function ``call(nc, q, mu, r, u, settings, result)`` solving with this W."""
    if _is_sparse(W):
        if tuple(W.shape) != (n, n):
            raise _size_error(
                "W is %d x %d; %d x %d expected (3 rows per contact)" % (W.shape + (n, n))
            )
        if np.issubdtype(W.dtype, np.complexfloating):
            raise TypeError("W must be real, got a complex sparse matrix")
        if W.format == "coo":
            rows = _index_array(W.row)
            cols = _index_array(W.col)
            values = np.ascontiguousarray(W.data, dtype=np.float64)

            def call(nc, q, mu, r, u, settings, result):
                """Calls the C solve function for this storage."""
                return lib.fc3d_solve_coo(
                    nc, len(values), int64_ptr(rows), int64_ptr(cols), double_ptr(values),
                    double_ptr(q), double_ptr(mu), double_ptr(r), double_ptr(u), settings, result,
                )

            return call
        csr = W.tocsr()
        row_ptr = _index_array(csr.indptr)
        # scipy may keep unused room after row_ptr[-1] entries: pass exactly the stored ones.
        nnz = int(row_ptr[-1])
        col_idx = _index_array(csr.indices[:nnz])
        values = np.ascontiguousarray(csr.data[:nnz], dtype=np.float64)

        def call(nc, q, mu, r, u, settings, result):
            """Calls the C solve function for this storage."""
            return lib.fc3d_solve_csr(
                nc, len(values), int64_ptr(row_ptr), int64_ptr(col_idx), double_ptr(values),
                double_ptr(q), double_ptr(mu), double_ptr(r), double_ptr(u), settings, result,
            )

        return call

    dense = _real_array(W, "W")
    if dense.ndim != 2 or dense.shape != (n, n):
        raise _size_error(
            "W has shape %s; (%d, %d) expected (3 rows per contact)" % (dense.shape, n, n)
        )
    # The C entry reads W column-major: any numpy layout is converted (no copy when W is
    # already Fortran-ordered float64).
    dense = np.asfortranarray(dense, dtype=np.float64)

    def call(nc, q, mu, r, u, settings, result):
        """Calls the C solve function for this storage."""
        return lib.fc3d_solve_dense(
            nc, double_ptr(dense), double_ptr(q), double_ptr(mu), double_ptr(r), double_ptr(u),
            settings, result,
        )

    return call


# ----------------------------------------------------------------------------------------------
# Settings.


class _Settings:
    """An ``Fc3dSettings*`` for one solve, released on exit."""

    def __init__(self, sid):
        """Creates the settings of solver ``sid`` with its Siconos defaults."""
        self.handle = lib.fc3d_settings_new(sid)
        if not self.handle:
            raise _native.last_error()

    def __enter__(self):
        """Context manager: returns self."""
        return self

    def __exit__(self, *exc):
        """Releases the settings."""
        lib.fc3d_settings_free(self.handle)
        self.handle = None

    def set(self, name, value):
        """Sets the setting ``name`` (a name of ``fc3d_settings_set``) to the number ``value``."""
        if isinstance(value, bool):
            value = int(value)
        if not isinstance(value, numbers.Real):
            raise TypeError("setting %s: %r is not a number" % (name, value))
        check(lib.fc3d_settings_set(self.handle, name.encode("utf-8"), float(value)))


def _integer(value, what):
    """``value`` as a Python int in the int64 range, for an integer setting ``what``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError("%s must be an integer, not %r" % (what, value))
    if isinstance(value, numbers.Integral):
        value = int(value)
    elif float(value).is_integer():
        value = int(value)
    else:
        raise Fc3dError("fc3d: %s = %r must be an integer" % (what, value), ERR_INVALID_OPTION)
    if not _INT64_RANGE[0] <= value <= _INT64_RANGE[1]:
        raise Fc3dError("fc3d: %s = %d is out of range" % (what, value), ERR_INVALID_OPTION)
    return value


def _items(value, key):
    """The ``(index, value)`` pairs of the option ``key``: a mapping or a sequence of pairs."""
    if isinstance(value, Mapping):
        return list(value.items())
    try:
        return [(k, v) for k, v in value]
    except (TypeError, ValueError):
        raise TypeError(
            "%s must be a mapping {index: value} (or a sequence of (index, value) pairs), not %r"
            % (key, value)
        ) from None


def _configure(settings, tol, max_iter, time_budget, options):
    """Applies the arguments of :func:`solve` to the settings, in a fixed order."""
    if tol is not None:
        check(lib.fc3d_settings_set_tolerance(settings.handle, float(tol)))
    if max_iter is not None:
        check(lib.fc3d_settings_set_max_iter(settings.handle, _integer(max_iter, "max_iter")))
    if time_budget is not None:
        check(lib.fc3d_settings_set_time_budget(settings.handle, float(time_budget)))
    options = dict(options)
    # The local solver first: choosing it resets the local solver's parameters.
    local = options.pop("local_solver", None)
    if local is not None:
        check(lib.fc3d_settings_set_local_solver(settings.handle, local_solver_id(local)))
    for key, value in options.items():
        if key in _INDEXED_OPTIONS:
            for index, v in _items(value, key):
                settings.set("%s[%d]" % (key, _integer(index, key + " index")), v)
        else:
            settings.set(key, value)


# ----------------------------------------------------------------------------------------------
# Solving.


def solve(
    W,
    q=None,
    mu=None,
    solver="AUTO",
    tol=None,
    max_iter=None,
    time_budget=None,
    r0=None,
    **options
):
    """Solves the frictional contact problem FC(W, q, mu): finds ``r``, ``u = W r + q`` with, for
    every contact, Signorini's condition in the normal direction and Coulomb's law (coefficient
    ``mu``) in the tangent plane. Components are ordered per contact: normal, tangent 1, tangent 2.

    Args:
        W: the ``3nc x 3nc`` Delassus matrix: a numpy array (any memory layout; converted to
            column-major float64), or a scipy.sparse matrix or array of any format (COO is passed
            as triplets, every other format as compressed rows); or a :class:`Problem` from
            :func:`read_problem`, then ``q`` and ``mu`` are left out.
        q: the free velocity, ``3nc`` values.
        mu: the friction coefficients, ``nc`` values (>= 0), or one number for every contact.
        solver: a name of ``fc3d.SOLVERS`` (any case, ``-`` or ``_``; Siconos' name strings
            such as ``"FC3D_DeSaxceFixedPoint"`` too) or a Siconos solver id. The default,
            ``"AUTO"`` (590), chooses and switches between methods from the problem, the
            tolerance and the budget. The names, with their ids:

            {solvers}
        tol: tolerance on the relative natural-map error (Siconos' ``dparam[0]``); None keeps the
            solver's Siconos default (AUTO's: 1e-4).
        max_iter: iteration limit (``iparam[0]``); None keeps the solver's default (AUTO 10000
            iterations over all its stages, NSGS 1000 sweeps; note that NSN_NM's is a single
            Newton step, as in Siconos).
        time_budget: wall-clock budget in seconds (0 or None: none). When it runs out the best
            iterate is returned with ``info == 2``.
        r0: initial reaction (warm start), ``3nc`` values; zeros when None. Not modified.
        **options: further settings of the C entry:

            * ``local_solver``: NSGS's local solver, a name of ``fc3d.LOCAL_SOLVERS`` or an alias
              (``"HYBRID"`` 565 the default, ``"NSN_GP"`` 551, ``"SBP"`` 552, ``"EBP"`` 571, ...)
              or a Siconos id;
            * ``iparam``, ``dparam``, ``local_iparam``, ``local_dparam``: mappings
              ``{index: value}`` of Siconos' parameter slots of the solver or of its local solver,
              e.g. ``iparam={4: 1}, dparam={8: 1.3}`` (NSGS with relaxation 1.3);
            * any other name is passed as is to ``fc3d_settings_set``, e.g.
              ``**{"iparam[7]": 1}``.

    Returns:
        a :class:`Result` (``r``, ``u``, ``info``, ``error``, ``iterations``, ``seconds``,
        ``converged``). Not reaching the tolerance is not an exception: check ``converged``.

    Raises:
        Fc3dError: input the library rejects, with its message and code: a negative or
            non-finite mu (``ERR_INVALID_PROBLEM``, ``ERR_NON_FINITE``), NaN or infinity in W, q
            or r0 (``ERR_NON_FINITE``), arrays of inconsistent sizes (``ERR_INVALID_SIZE``),
            an inconsistent sparse structure (``ERR_INVALID_STORAGE``), an unknown solver
            (``ERR_UNSUPPORTED_SOLVER``), an unknown or out-of-range option
            (``ERR_INVALID_OPTION``).
        TypeError: arguments of the wrong type (complex arrays, non-numeric options).

    The library releases the GIL while it solves (ctypes), so independent problems can be
    solved in parallel threads.
    """
    sid = solver_id(solver)
    if isinstance(W, Problem):
        if q is not None or mu is not None:
            raise TypeError("solve(problem, ...): q and mu come from the problem; pass arrays "
                            "to solve a modified problem")
        problem = W
        nc = problem.n_contacts
        handle = problem.handle

        def call(nc_, q_, mu_, r, u, settings, result):
            """Calls the C solve function for this storage."""
            return lib.fc3d_problem_solve(handle, double_ptr(r), double_ptr(u), settings, result)

        qv = muv = None
    else:
        if q is None or mu is None:
            raise TypeError("solve(W, q, mu, ...): q and mu are required with a matrix W")
        qv = _vector(q, "q", None)
        if qv.shape[0] % 3 != 0:
            raise _size_error("q has %d entries: 3 per contact expected" % qv.shape[0])
        nc = qv.shape[0] // 3
        mu_array = _real_array(mu, "mu")
        if mu_array.ndim == 0:
            muv = np.full(nc, float(mu_array), dtype=np.float64)
        else:
            muv = _vector(mu_array, "mu", None)
            if muv.shape[0] != nc:
                raise _size_error(
                    "mu has %d entries but q has %d = 3 x %d: one mu per contact expected"
                    % (muv.shape[0], qv.shape[0], nc)
                )
        call = _prepare_matrix(W, 3 * nc)
    n = 3 * nc
    if r0 is None:
        r = np.zeros(n, dtype=np.float64)
    else:
        r = np.array(_vector(r0, "r0", n), dtype=np.float64, copy=True)
    u = np.zeros(n, dtype=np.float64)
    result = Fc3dResult()
    with _Settings(sid) as settings:
        _configure(settings, tol, max_iter, time_budget, options)
        info = check(call(nc, qv, muv, r, u, settings.handle, result))
    return Result(r, u, info, result.error, result.iterations, result.seconds, sid)


def _list_solvers_in_docstring():
    """Writes the library's solver names (``fc3d.SOLVERS``, built at import) into the docstring
    of :func:`solve`, so that ``help(fc3d.solve)`` lists them; no-op under ``python -OO``."""
    if solve.__doc__ is None:  # pragma: no cover
        return
    entries = ["%s (%d)" % (name, sid) for name, sid in sorted(SOLVERS.items(), key=lambda e: e[1])]
    lines = [""]
    for k, entry in enumerate(entries):
        text = entry + ("," if k + 1 < len(entries) else "")
        if lines[-1] and len(lines[-1]) + 1 + len(text) > 80:
            lines.append(text)
        else:
            lines[-1] = (lines[-1] + " " + text).lstrip()
    solve.__doc__ = solve.__doc__.replace("{solvers}", "\n            ".join(lines))


_list_solvers_in_docstring()
