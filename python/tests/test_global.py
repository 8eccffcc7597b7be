"""fc3d.solve_global: the global form (M, H, q, b, mu) with known answers, dense and sparse input,
the relation M v = q + H r, and the library's refusals."""

import numpy as np
import pytest

import fc3d

try:
    import scipy.sparse as scipy_sparse
except ImportError:  # scipy is optional: the sparse tests are skipped without it
    scipy_sparse = None

needs_scipy = pytest.mark.skipif(scipy_sparse is None, reason="scipy is not installed")

# Solvers that reach 1e-10 on the sliding contact below (615 and 613's defaults solve the convex
# relaxation; the VI ids need many iterations).
EXACT = ["NSGS_WR", "PROX_WR", "NSN_AC_WR", "TFP_WR", "NSGS", "NSN_AC", "ADMM_WR", "ADMM"]


def sliding_contact(copies=1):
    """``copies`` independent bodies of mass 2 (3 unknowns each) with one contact each, H = I,
    q = M v_free with v_free = (-1, 2, 0), mu = 0.5: reduced, W = I / 2, q_loc = v_free; every
    contact slides with r = (2, -1, 0), u = (0, 1.5, 0), v = (0, 1.5, 0)."""
    n = 3 * copies
    M = 2.0 * np.eye(n)
    H = np.eye(n)
    q = np.tile([-2.0, 4.0, 0.0], copies)
    b = np.zeros(n)
    mu = np.full(copies, 0.5)
    expected = (np.tile([2.0, -1.0, 0.0], copies), np.tile([0.0, 1.5, 0.0], copies))
    return (M, H, q, b, mu), expected


@pytest.mark.parametrize("solver", EXACT)
def test_sliding_contact_every_exact_solver(solver):
    """The known solution from every global solver of the exact Coulomb problem."""
    (M, H, q, b, mu), (r_exact, u_exact) = sliding_contact()
    res = fc3d.solve_global(M, H, q, b, mu, solver=solver, tol=1e-10, max_iter=10000)
    assert res.converged and res.status == "converged", res
    assert res.error <= 1e-10
    np.testing.assert_allclose(res.r, r_exact, atol=1e-6)
    np.testing.assert_allclose(res.u, u_exact, atol=1e-6)
    np.testing.assert_allclose(res.v, u_exact, atol=1e-6)
    np.testing.assert_allclose(M @ res.v, q + H @ res.r, atol=1e-12)
    assert res.solver == fc3d.GLOBAL_SOLVERS[solver] and res.solver_name == solver
    assert "GlobalResult(%s" % solver in repr(res)


def test_defaults_names_and_warm_start():
    """Plain lists, a scalar mu, the default solver (600), Siconos' name strings and r0."""
    (M, H, q, b, _), (r_exact, _) = sliding_contact()
    res = fc3d.solve_global(M.tolist(), H.tolist(), list(q), list(b), 0.5, tol=1e-12)
    assert res.solver == 600 and res.n_contacts == 1
    np.testing.assert_allclose(res.r, r_exact, atol=1e-8)
    for name in ("GFC3D_NSGS_WR", "gfc3d-nsgs-wr", "SICONOS_GLOBAL_FRICTION_3D_NSGS_WR", 600, "600"):
        assert fc3d.global_solver_id(name) == 600
    assert fc3d.global_solver_id("GFC3D ADMM") == 613
    r0 = r_exact.copy()
    warm = fc3d.solve_global(M, H, q, b, 0.5, solver="NSGS_WR", tol=1e-12, r0=r0)
    assert warm.converged and warm.iterations <= res.iterations
    np.testing.assert_array_equal(r0, r_exact)


@needs_scipy
def test_sparse_input_of_any_format_gives_the_dense_answer():
    """M and H as scipy sparse (CSR, CSC, COO) give the same result as dense input; the inputs
    are left unchanged."""
    (M, H, q, b, mu), (r_exact, u_exact) = sliding_contact(copies=4)
    dense = fc3d.solve_global(M, H, q, b, mu, solver="NSN_AC_WR", tol=1e-12)
    for fmt in ("csr", "csc", "coo"):
        Ms = scipy_sparse.csr_matrix(M).asformat(fmt)
        Hs = scipy_sparse.csr_matrix(H).asformat(fmt)
        before = (Ms.copy(), Hs.copy())
        res = fc3d.solve_global(Ms, Hs, q, b, mu, solver="NSN_AC_WR", tol=1e-12)
        np.testing.assert_allclose(res.r, dense.r, atol=1e-12)
        np.testing.assert_allclose(res.v, dense.v, atol=1e-12)
        np.testing.assert_allclose(res.u, u_exact, atol=1e-8)
        assert (Ms != before[0]).nnz == 0 and (Hs != before[1]).nnz == 0


@needs_scipy
def test_rigid_bodies_with_coupled_contacts():
    """Bodies of 6 unknowns (mass and inertia blocks), contacts sharing bodies: every exact
    solver converges, M v = q + H r holds and u = H^T v + b."""
    rng = np.random.default_rng(3)
    bodies, nc = 5, 6
    blocks = []
    for _ in range(bodies):
        a = rng.standard_normal((3, 3))
        blocks.append(np.block([[2.0 * np.eye(3), np.zeros((3, 3))],
                                [np.zeros((3, 3)), a @ a.T + np.eye(3)]]))
    M = scipy_sparse.block_diag(blocks, format="csr")
    H = np.zeros((6 * bodies, 3 * nc))
    for c in range(nc):
        for k in (c % bodies, (c + 1) % bodies):
            H[6 * k:6 * k + 6, 3 * c:3 * c + 3] = rng.standard_normal((6, 3))
    Hs = scipy_sparse.csr_matrix(H)
    v_free = rng.standard_normal(6 * bodies)
    q = M @ v_free
    b = np.zeros(3 * nc)
    b[0::3] = -0.1
    mu = np.full(nc, 0.3)
    for solver in ("NSGS_WR", "NSN_AC_WR", "NSN_AC"):
        res = fc3d.solve_global(M, Hs, q, b, mu, solver=solver, tol=1e-9, max_iter=20000)
        assert res.converged, (solver, res)
        np.testing.assert_allclose(M @ res.v, q + H @ res.r, atol=1e-10)
        np.testing.assert_allclose(res.u, H.T @ res.v + b, atol=1e-10)


def test_refusals_carry_the_librarys_reason():
    """A singular M, wrong sizes, a local id, 601 and an unknown name are Fc3dErrors."""
    (M, H, q, b, mu), _ = sliding_contact()
    with pytest.raises(fc3d.Fc3dError) as e:
        fc3d.solve_global(np.zeros((3, 3)), H, q, b, mu)
    assert "singular" in e.value.message.lower()
    with pytest.raises(fc3d.Fc3dError) as e:
        fc3d.solve_global(M, H[:, :2], q, b, mu)
    assert e.value.code == fc3d.ERR_INVALID_SIZE
    with pytest.raises(fc3d.Fc3dError) as e:
        fc3d.solve_global(M, H, q, b, mu, solver=500)
    assert e.value.code == fc3d.ERR_UNSUPPORTED_SOLVER and "global" in e.value.message
    with pytest.raises(fc3d.Fc3dError) as e:
        fc3d.solve_global(M, H, q, b, mu, solver=601)
    assert e.value.code == fc3d.ERR_UNSUPPORTED_SOLVER
    with pytest.raises(fc3d.Fc3dError):
        fc3d.solve_global(M, H, q, b, mu, solver="NO_SUCH")
    with pytest.raises(fc3d.Fc3dError) as e:
        fc3d.solve_global(M, H, [np.nan, 0.0, 0.0], b, mu)
    assert e.value.code == fc3d.ERR_NON_FINITE
