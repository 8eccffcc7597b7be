"""Bad input raises fc3d.Fc3dError with the library's message and code."""

import numpy as np
import pytest

import fc3d

try:
    import scipy.sparse as scipy_sparse
except ImportError:
    scipy_sparse = None

W1 = np.eye(3)
Q1 = np.array([-1.0, 2.0, 0.0])
MU1 = np.array([0.5])


def raises(code, match, **overrides):
    """Solves the one-contact problem with ``overrides`` and checks the Fc3dError raised."""
    kwargs = dict(W=W1, q=Q1, mu=MU1)
    kwargs.update(overrides)
    with pytest.raises(fc3d.Fc3dError, match=match) as info:
        fc3d.solve(**kwargs)
    assert info.value.code == code, info.value
    assert str(info.value) == info.value.message and info.value.message
    assert info.value.code_name.startswith("FC3D_ERR_")
    return info.value


def test_negative_mu():
    """mu < 0 is rejected by the library with ERR_INVALID_PROBLEM."""
    e = raises(fc3d.ERR_INVALID_PROBLEM, "negative friction coefficient mu\\[0\\] = -0.5",
               mu=[-0.5])
    assert e.code_name == "FC3D_ERR_INVALID_PROBLEM"


def test_nan_in_q():
    """A NaN in q is rejected with ERR_NON_FINITE and its index."""
    raises(fc3d.ERR_NON_FINITE, "non-finite value in q at index 1", q=[-1.0, np.nan, 0.0])


def test_non_finite_w_mu_r0():
    """Non-finite values in W (every storage), mu and r0 are rejected."""
    w = W1.copy()
    w[2, 2] = np.inf
    raises(fc3d.ERR_NON_FINITE, "non-finite value in W", W=w)
    raises(fc3d.ERR_NON_FINITE, "non-finite value in mu", mu=[np.nan])
    raises(fc3d.ERR_NON_FINITE, "non-finite value in initial reaction", r0=[0.0, np.nan, 0.0])
    if scipy_sparse is not None:
        raises(fc3d.ERR_NON_FINITE, "non-finite value in W", W=scipy_sparse.csr_matrix(w))
        raises(fc3d.ERR_NON_FINITE, "non-finite value in W", W=scipy_sparse.coo_matrix(w))


def test_wrong_sizes():
    """Inconsistent lengths and shapes raise ERR_INVALID_SIZE before any C call."""
    raises(fc3d.ERR_INVALID_SIZE, "q has 4 entries: 3 per contact expected", q=[1.0, 2, 3, 4])
    raises(fc3d.ERR_INVALID_SIZE, "mu has 2 entries", mu=[0.5, 0.5])
    raises(fc3d.ERR_INVALID_SIZE, "W has shape \\(6, 6\\); \\(3, 3\\) expected", W=np.eye(6))
    raises(fc3d.ERR_INVALID_SIZE, "W has shape \\(3,\\)", W=np.ones(3))
    raises(fc3d.ERR_INVALID_SIZE, "r0 has 2 entries, 3 expected", r0=[0.0, 0.0])
    raises(fc3d.ERR_INVALID_SIZE, "q must be a 1-D array", q=np.zeros((1, 3)))
    if scipy_sparse is not None:
        raises(fc3d.ERR_INVALID_SIZE, "W is 6 x 6; 3 x 3 expected",
               W=scipy_sparse.identity(6, format="csr"))


@pytest.mark.skipif(scipy_sparse is None, reason="scipy is not installed")
def test_inconsistent_sparse_structure():
    """A CSR column index outside the matrix is rejected by the library."""
    csr = scipy_sparse.csr_matrix(W1)
    csr.indices[1] = 7  # a column outside the matrix
    raises(fc3d.ERR_INVALID_STORAGE, "outside a 3x3 matrix", W=csr)


def test_unknown_solver():
    """Unknown solver names (Python) and ids (library) raise ERR_UNSUPPORTED_SOLVER."""
    e = raises(fc3d.ERR_UNSUPPORTED_SOLVER, "unknown solver 'NOPE'", solver="NOPE")
    assert "NSGS (500)" in e.message  # the message lists the known names
    raises(fc3d.ERR_UNSUPPORTED_SOLVER, "solver id 599", solver=599)
    raises(fc3d.ERR_UNSUPPORTED_SOLVER, "unfinished", solver=501)  # Siconos' NSGSV, rejected with the reason


def test_bad_options():
    """Out-of-range or unknown settings raise ERR_INVALID_OPTION with the slot named."""
    raises(fc3d.ERR_INVALID_OPTION, "tolerance \\(dparam\\[0\\]\\) = -1", tol=-1.0)
    raises(fc3d.ERR_INVALID_OPTION, "max_iter = -1", max_iter=-1)
    raises(fc3d.ERR_INVALID_OPTION, "time budget", time_budget=-1.0)
    raises(fc3d.ERR_INVALID_OPTION, "parameter index 99", iparam={99: 1})
    raises(fc3d.ERR_INVALID_OPTION, "iparam\\[4\\] = 1.5 must be an integer", iparam={4: 1.5})
    raises(fc3d.ERR_INVALID_OPTION, "relaxation \\(dparam\\[8\\]\\)", solver="NSGS",
           iparam={4: 1}, dparam={8: 2.5})
    raises(fc3d.ERR_INVALID_OPTION, "unknown setting 'colour'", colour=1)
    raises(fc3d.ERR_INVALID_OPTION, "unknown local solver 'NOPE'", local_solver="NOPE")
    raises(fc3d.ERR_INVALID_OPTION, "500 is not a local \\(one-contact\\) solver id", solver="NSGS",
           local_solver=500)
    raises(fc3d.ERR_INVALID_OPTION, "has no local", solver="NSN_AC", local_solver="HYBRID")


def test_type_errors():
    """Arguments of the wrong type raise TypeError."""
    with pytest.raises(TypeError):
        fc3d.solve(W1 + 0j, Q1, MU1)
    with pytest.raises(TypeError):
        fc3d.solve(W1, Q1, MU1, iparam=5)
    with pytest.raises(TypeError):
        fc3d.solve(W1, Q1, MU1, tolerance="small")
    with pytest.raises(TypeError):
        fc3d.solve(W1, Q1)  # mu missing
    with pytest.raises(TypeError):
        fc3d.solve(W1, Q1, MU1, solver=5.5)


def test_error_is_an_exception_with_code():
    """Fc3dError carries its code and the code's name."""
    e = fc3d.Fc3dError("fc3d: something", fc3d.ERR_PARSE)
    assert isinstance(e, Exception) and e.code == -8 and e.code_name == "FC3D_ERR_PARSE"
    assert "something" in repr(e)
