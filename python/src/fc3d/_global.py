"""The global formulation: :func:`solve_global` and :class:`GlobalResult`.

Hosts that keep the bodies' velocities as unknowns (finite elements, multibody codes, Siconos'
own ``GlobalFrictionContact``) give the mass (or iteration) matrix ``M`` (``n x n``), the contact
operator ``H`` (``n x 3nc``), ``q``, ``b`` and ``mu``, and get ``v``, ``u = H^T v + b`` and ``r`` with
``M v = q + H r``. The C library solves it (``fc3d_solve_global_csr`` of fc3d_native.h) with
Siconos' global solver ids 600-615 (``gfc3d_driver``); this module converts the arrays.
"""

import numpy as np

from ._api import _Settings, _configure, _is_sparse, _real_array, _size_error, _vector
from ._errors import ERR_UNSUPPORTED_SOLVER, STATUS_NAMES
from ._native import Fc3dResult, check, double_ptr, int64_ptr, lib
from ._solvers import _lookup

__all__ = ["GLOBAL_SOLVERS", "GlobalResult", "global_solver_id", "solve_global"]

#: The global solvers (Siconos' ``gfc3d_driver`` ids) by name: Siconos' name without its
#: ``GFC3D_`` prefix -> id. The ``_WR`` ids reduce the problem to FC(H^T M^-1 H, H^T M^-1 q + b,
#: mu) (M factored, never inverted) and run the local solver of the same name; the others work
#: on ``(v, u, r)``. 601 and the GAMS ids 608/609 are refused by the library, with the reason.
GLOBAL_SOLVERS = {
    "NSGS_WR": 600,
    "PROX_WR": 602,
    "DSFP_WR": 603,
    "TFP_WR": 604,
    "NSGS": 605,
    "NSN_AC_WR": 606,
    "NSN_AC": 607,
    "VI_FPP": 610,
    "VI_EG": 611,
    "ACLMFP": 612,
    "ADMM": 613,
    "ADMM_WR": 614,
    "IPM": 615,
}


def _normalize_global(name):
    """Upper case, ``-`` and spaces as ``_``, the prefixes ``SICONOS_GLOBAL_FRICTION_3D_`` /
    ``GFC3D_`` removed."""
    key = name.strip().upper().replace("-", "_").replace(" ", "_")
    for prefix in ("SICONOS_GLOBAL_FRICTION_3D_", "GLOBAL_FRICTION_3D_", "GFC3D_"):
        if key.startswith(prefix):
            return key[len(prefix):]
    return key


def global_solver_id(solver):
    """The Siconos id of a global solver: a name of :data:`GLOBAL_SOLVERS` (any case, with or
    without ``GFC3D_``; Siconos' strings such as ``"GFC3D ADMM"`` too) or an integer id (checked
    by the library)."""
    if isinstance(solver, str) and not solver.strip().isdigit():
        solver = _normalize_global(solver)
    return _lookup(solver, GLOBAL_SOLVERS, {}, "global solver", ERR_UNSUPPORTED_SOLVER)


class GlobalResult:
    """The outcome of :func:`solve_global`.

    Attributes:
        r: the reaction, ``3 * n_contacts`` values (per contact: normal, tangent 1, tangent 2).
        u: the local velocity ``H^T v + b``.
        v: the global velocity, ``n`` values, with ``M v = q + H r`` to round-off.
        info: 0 converged (``error <= tol``), 1 iteration limit reached, 2 time budget spent,
            3 the convex relaxation is solved but ``(r, u)`` is not a Coulomb solution (615's
            and 613's defaults solve the relaxation).
        error: Siconos' global error (``gfc3d_compute_error``) of ``(r, u, v)``.
        iterations, seconds, solver: as in :class:`fc3d.Result` (``solver`` a global id).
    """

    __slots__ = ("r", "u", "v", "info", "error", "iterations", "seconds", "solver")

    def __init__(self, r, u, v, info, error, iterations, seconds, solver):
        """Wraps the arrays and numbers of one global solve."""
        self.r, self.u, self.v = r, u, v
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
        """``info`` as a word (``converged``, ``max_iter``, ``time_budget``,
        ``relaxed_not_coulomb``)."""
        return STATUS_NAMES.get(self.info, str(self.info))

    @property
    def solver_name(self):
        """The global solver's name (``"NSGS_WR"``, ``"IPM"``, ...)."""
        for name, sid in GLOBAL_SOLVERS.items():
            if sid == self.solver:
                return name
        return str(self.solver)

    @property
    def n_contacts(self):
        """Number of contacts (``len(r) // 3``)."""
        return len(self.r) // 3

    def __repr__(self):
        """A one-line summary."""
        return (
            "GlobalResult(%s, info=%d (%s), iterations=%d, error=%.3g, seconds=%.3g, nc=%d, n=%d)"
            % (self.solver_name, self.info, self.status, self.iterations, self.error,
               self.seconds, self.n_contacts, len(self.v))
        )


def _csr_arrays(A, shape, what):
    """``(row_ptr, col_idx, values)`` of ``A`` (scipy sparse of any format, or dense) in compressed
    rows, int64 / float64, checked to have ``shape``."""
    if _is_sparse(A):
        if tuple(A.shape) != shape:
            raise _size_error("%s is %d x %d; %d x %d expected" % ((what,) + tuple(A.shape) + shape))
        if np.issubdtype(A.dtype, np.complexfloating):
            raise TypeError("%s must be real, got a complex sparse matrix" % what)
        csr = A.tocsr()
        row_ptr = np.ascontiguousarray(csr.indptr, dtype=np.int64)
        nnz = int(row_ptr[-1])
        col_idx = np.ascontiguousarray(csr.indices[:nnz], dtype=np.int64)
        values = np.ascontiguousarray(csr.data[:nnz], dtype=np.float64)
        return row_ptr, col_idx, values
    dense = _real_array(A, what)
    if dense.ndim != 2 or dense.shape != shape:
        raise _size_error("%s has shape %s; %s expected" % (what, dense.shape, shape))
    dense = np.asarray(dense, dtype=np.float64)
    # The stored pattern is what the library finds M's blocks from: a dense array's exact zeros
    # are left out (NaN is kept, and refused by the library).
    mask = dense != 0.0
    row_ptr = np.zeros(shape[0] + 1, dtype=np.int64)
    np.cumsum(mask.sum(axis=1), out=row_ptr[1:])
    col_idx = np.ascontiguousarray(np.nonzero(mask)[1], dtype=np.int64)
    values = np.ascontiguousarray(dense[mask], dtype=np.float64)
    return row_ptr, col_idx, values


def solve_global(
    M,
    H,
    q,
    b,
    mu,
    solver="NSGS_WR",
    tol=None,
    max_iter=None,
    time_budget=None,
    r0=None,
    **options
):
    """Solves the global frictional contact problem: finds ``v``, ``u``, ``r`` with
    ``M v = q + H r``, ``u = H^T v + b`` and, per contact, Signorini's condition and Coulomb's law
    between ``u`` and ``r`` (Siconos' ``gfc3d_driver``).

    Args:
        M: the ``n x n`` invertible matrix (mass or iteration matrix; not necessarily symmetric),
            a scipy.sparse matrix or array of any format or a dense array. Usually block diagonal
            (one block per body): the library finds the blocks and factors them one by one.
        H: the ``n x 3nc`` contact operator (same types).
        q: ``n`` values. b: ``3nc`` values. mu: ``nc`` values (>= 0), or one number.
        solver: a name of :data:`fc3d.GLOBAL_SOLVERS` or a global id (600-615); the default,
            ``"NSGS_WR"`` (600), reduces the problem and runs NSGS.
        tol, max_iter, time_budget, r0, **options: as in :func:`fc3d.solve` (the tolerance is on
            Siconos' global error; for a ``_WR`` id ``local_solver`` and ``local_*param`` set its
            local solver's).

    Returns:
        a :class:`GlobalResult`. M, H and the input arrays are not modified.

    Raises:
        Fc3dError: input the library rejects (a singular M: ``ERR_INVALID_PROBLEM``), with its
            message; TypeError for arguments of the wrong type.
    """
    sid = global_solver_id(solver)
    qv = _vector(q, "q", None)
    n = qv.shape[0]
    bv = _vector(b, "b", None)
    if bv.shape[0] % 3 != 0:
        raise _size_error("b has %d entries: 3 per contact expected" % bv.shape[0])
    nc = bv.shape[0] // 3
    mu_array = _real_array(mu, "mu")
    if mu_array.ndim == 0:
        muv = np.full(nc, float(mu_array), dtype=np.float64)
    else:
        muv = _vector(mu_array, "mu", None)
        if muv.shape[0] != nc:
            raise _size_error(
                "mu has %d entries but b has %d = 3 x %d: one mu per contact expected"
                % (muv.shape[0], bv.shape[0], nc)
            )
    m_ptr, m_idx, m_val = _csr_arrays(M, (n, n), "M")
    h_ptr, h_idx, h_val = _csr_arrays(H, (n, 3 * nc), "H")
    if r0 is None:
        r = np.zeros(3 * nc, dtype=np.float64)
    else:
        r = np.array(_vector(r0, "r0", 3 * nc), dtype=np.float64, copy=True)
    u = np.zeros(3 * nc, dtype=np.float64)
    v = np.zeros(n, dtype=np.float64)
    result = Fc3dResult()
    with _Settings(sid) as settings:
        _configure(settings, tol, max_iter, time_budget, options)
        info = check(
            lib.fc3d_solve_global_csr(
                n, nc,
                len(m_val), int64_ptr(m_ptr), int64_ptr(m_idx), double_ptr(m_val),
                len(h_val), int64_ptr(h_ptr), int64_ptr(h_idx), double_ptr(h_val),
                double_ptr(qv), double_ptr(bv), double_ptr(muv),
                double_ptr(r), double_ptr(u), double_ptr(v), settings.handle, result,
            )
        )
    return GlobalResult(r, u, v, info, result.error, result.iterations, result.seconds, sid)

