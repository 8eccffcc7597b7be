"""fc3d.solve on problems built in Python: known answers, storages, options, warm start, budget."""

import threading
import time

import numpy as np
import pytest

import fc3d
from conftest import random_problem

try:
    import scipy.sparse as scipy_sparse
except ImportError:  # scipy is optional: the sparse tests are skipped without it
    scipy_sparse = None

needs_scipy = pytest.mark.skipif(scipy_sparse is None, reason="scipy is not installed")

# Solvers that solve the Coulomb problem (SOCLCP solves a relaxation, tested apart).
COULOMB_SOLVERS = [name for name in fc3d.SOLVERS if name != "SOCLCP"]


@pytest.mark.parametrize("solver", COULOMB_SOLVERS)
def test_single_sliding_contact(solver):
    """W = I, q = (-1, 2, 0), mu = 0.5: the contact slides, r = (1, -0.5, 0), u = (0, 1.5, 0)."""
    res = fc3d.solve(np.eye(3), np.array([-1.0, 2.0, 0.0]), np.array([0.5]), solver=solver,
                     tol=1e-10)
    assert res.converged and res.info == fc3d.OK and res.status == "converged"
    assert res.error <= 1e-10
    np.testing.assert_allclose(res.r, [1.0, -0.5, 0.0], atol=1e-7)
    np.testing.assert_allclose(res.u, [0.0, 1.5, 0.0], atol=1e-7)
    assert res.solver == fc3d.SOLVERS[solver] and res.solver_name == solver
    assert res.iterations >= 0 and res.seconds >= 0.0


def test_single_contact_defaults_and_lists():
    """Plain lists, a scalar mu and the default solver (AUTO) with the default tolerance."""
    res = fc3d.solve([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [-1, 2, 0], 0.5)
    np.testing.assert_allclose(res.r, [1.0, -0.5, 0.0], atol=1e-6)
    assert res.solver == 590 and res.n_contacts == 1
    assert "AUTO" in repr(res)


def test_solvers_are_the_librarys():
    """fc3d.SOLVERS is the library's list: every id fc3d_settings_new accepts, AUTO included,
    each reachable by its short name and by Siconos' name string; help(fc3d.solve) lists them."""
    listed = fc3d._native.solvers()
    assert sorted(fc3d.SOLVERS.values()) == [sid for sid, _, _ in listed]
    assert fc3d.SOLVERS["AUTO"] == 590 and len(fc3d.SOLVERS) >= 20
    for sid, constant, name in listed:
        assert fc3d.solver_id(constant) == sid and fc3d.solver_id(name) == sid
    for name, sid in fc3d.SOLVERS.items():
        assert "%s (%d)" % (name, sid) in fc3d.solve.__doc__
    # Ids the library does not solve at top level are refused by it, with its reason.
    accepted = set(fc3d.SOLVERS.values())
    for sid in (400, 501, 550, 3000, 600):
        assert sid not in accepted


def test_soclcp_reports_relaxation_not_coulomb():
    """SOCLCP (517) solves the relaxation; on a sliding contact it says so with info 3."""
    res = fc3d.solve(np.eye(3), [-1.0, 2.0, 0.0], [0.5], solver="SOCLCP", tol=1e-10)
    assert res.info == fc3d.RELAXED_NOT_COULOMB and not res.converged
    assert res.status == "relaxed_not_coulomb"


@pytest.mark.parametrize(
    "alias, expected",
    [("NSGS", 500), ("nsgs", 500), ("NSN_AC", 504), ("NSN-AC", 504), ("nsn-ac", 504),
     ("SICONOS_FRICTION_3D_NSN_AC", 504), ("NSN_FB", 513), ("NSN_NM", 520), ("PROX", 502),
     ("TFP", 503), ("PFP", 522), ("ACLMFP", 516), ("SOCLCP", 517), ("ADMM", 523), ("DSFP", 505),
     ("VI_FPP", 506), ("VI-EG", 507), ("FPP", 511), ("EG", 512), (500, 500), ("504", 504),
     ("AUTO", 590), ("auto", 590), ("FC3D_AUTO", 590), ("HP", 508), ("NSN_AC_TEST", 521),
     ("QUARTIC", 562), ("QUARTIC_NU", 563), ("SICONOS_FRICTION_3D_ONECONTACT_QUARTIC", 562),
     ("FC3D_DeSaxceFixedPoint", 505), ("FC3D ADMM", 523), ("HyperplaneProjection", 508)],
)
def test_solver_names(alias, expected):
    """Solver names, aliases and ids map to Siconos ids."""
    assert fc3d.solver_id(alias) == expected


@pytest.mark.parametrize(
    "alias, expected",
    [("HYBRID", 565), ("NSN_GP_HYBRID", 565), ("NSN-GP", 551), ("NSN", 550), ("SBP", 552),
     ("PROJ-ITER", 553), ("SAL", 557), ("EBP", 571), ("EAL", 572), ("QUARTIC", 562),
     ("SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCone", 552), (551, 551)],
)
def test_local_solver_names(alias, expected):
    """Local solver names, aliases and ids map to Siconos ids."""
    assert fc3d.local_solver_id(alias) == expected


def _storages(w):
    """W in every input form the binding accepts."""
    forms = {
        "dense C order": np.ascontiguousarray(w),
        "dense Fortran order": np.asfortranarray(w),
        "dense transposed view": np.ascontiguousarray(w.T).T,
        "dense strided view": np.repeat(w, 2, axis=1)[:, ::2],
        "csr": scipy_sparse.csr_matrix(w),
        "coo": scipy_sparse.coo_matrix(w),
        "csc": scipy_sparse.csc_matrix(w),
        "bsr 3x3": scipy_sparse.bsr_matrix(w, blocksize=(3, 3)),
        "lil": scipy_sparse.lil_matrix(w),
        "dok": scipy_sparse.dok_matrix(w),
    }
    if hasattr(scipy_sparse, "csr_array"):
        forms["csr_array"] = scipy_sparse.csr_array(w)
        forms["coo_array"] = scipy_sparse.coo_array(w)
    return forms


@needs_scipy
@pytest.mark.parametrize("solver", ["NSGS", "NSN_AC"])
def test_dense_csr_coo_give_the_same_solution(problem30, solver):
    """Every storage of the same W gives the same r."""
    w, q, mu = problem30
    reference = fc3d.solve(w, q, mu, solver=solver, tol=1e-10)
    assert reference.converged and reference.error <= 1e-10
    for name, matrix in _storages(w).items():
        res = fc3d.solve(matrix, q, mu, solver=solver, tol=1e-10)
        assert res.converged, name
        np.testing.assert_allclose(res.r, reference.r, rtol=1e-9, atol=1e-12, err_msg=name)
        np.testing.assert_allclose(res.u, w @ res.r + q, rtol=1e-9, atol=1e-12, err_msg=name)


@needs_scipy
def test_sparse_unsorted_and_duplicate_entries(problem30):
    """COO duplicates are summed; CSR columns need not be sorted."""
    w, q, mu = problem30
    reference = fc3d.solve(w, q, mu, tol=1e-10)
    coo = scipy_sparse.coo_matrix(w)
    half = coo.data / 2
    rows = np.concatenate([coo.row, coo.row[::-1]])
    cols = np.concatenate([coo.col, coo.col[::-1]])
    data = np.concatenate([half, half[::-1]])
    duplicated = scipy_sparse.coo_matrix((data, (rows, cols)), shape=w.shape)
    res = fc3d.solve(duplicated, q, mu, tol=1e-10)
    np.testing.assert_allclose(res.r, reference.r, rtol=1e-9, atol=1e-12)

    csr = scipy_sparse.csr_matrix(w)
    for i in range(w.shape[0]):  # reverse the columns of every row
        start, end = csr.indptr[i], csr.indptr[i + 1]
        csr.indices[start:end] = csr.indices[start:end][::-1].copy()
        csr.data[start:end] = csr.data[start:end][::-1].copy()
    csr.has_sorted_indices = False
    res = fc3d.solve(csr, q, mu, tol=1e-10)
    np.testing.assert_allclose(res.r, reference.r, rtol=1e-9, atol=1e-12)


def test_inputs_are_not_modified(problem30):
    """W, q, mu and r0 are read, never written."""
    w, q, mu = problem30
    copies = [a.copy() for a in (w, q, mu)]
    r0 = np.full(len(q), 0.1)
    r0_copy = r0.copy()
    fc3d.solve(w, q, mu, r0=r0, tol=1e-8)
    for original, copy in zip((w, q, mu, r0), copies + [r0_copy]):
        np.testing.assert_array_equal(original, copy)


def test_warm_start_reduces_iterations(problem30):
    """Solving a perturbed problem from the previous solution takes fewer iterations."""
    w, q, mu = problem30
    first = fc3d.solve(w, q, mu, tol=1e-10)
    q2 = q + 1e-3 * np.random.default_rng(7).standard_normal(len(q))
    for solver in ("NSGS", "NSN_AC"):
        cold = fc3d.solve(w, q2, mu, solver=solver, tol=1e-10)
        warm = fc3d.solve(w, q2, mu, solver=solver, tol=1e-10, r0=first.r)
        assert cold.converged and warm.converged
        assert warm.iterations < cold.iterations, solver
        np.testing.assert_allclose(warm.r, cold.r, rtol=1e-6, atol=1e-8)
    # From a loose solution of the same problem, too.
    loose = fc3d.solve(w, q, mu, tol=1e-3)
    tight_cold = fc3d.solve(w, q, mu, tol=1e-10)
    tight_warm = fc3d.solve(w, q, mu, tol=1e-10, r0=loose.r)
    assert tight_warm.iterations < tight_cold.iterations


@pytest.mark.parametrize("budget", [0.1, 0.3])
def test_time_budget_is_respected(budget):
    """A solve that cannot converge (DSFP with a tiny fixed step, rho = dparam[3] = 1e-6) stops
    when the budget is spent, with info 2 and its best iterate."""
    w, q, mu = random_problem(100, seed=2)
    start = time.perf_counter()
    res = fc3d.solve(w, q, mu, solver="DSFP", tol=1e-12, max_iter=2 ** 31 - 1,
                     time_budget=budget, dparam={3: 1e-6})
    wall = time.perf_counter() - start
    assert res.info == fc3d.TIME_BUDGET_EXHAUSTED and res.status == "time_budget"
    assert not res.converged
    assert 0.9 * budget <= res.seconds <= budget + 0.5
    assert wall <= budget + 1.0
    assert np.all(np.isfinite(res.r)) and res.iterations > 0


def test_max_iter_and_options(problem30):
    """max_iter, iparam/dparam mappings, pass-through names, the local solver reach the library
    (NSGS's slots and local solver)."""
    w, q, mu = problem30
    one = fc3d.solve(w, q, mu, solver="NSGS", max_iter=1, tol=1e-10)
    assert one.info == fc3d.NOT_CONVERGED and one.iterations == 1 and one.status == "max_iter"
    # NSGS with over-relaxation: iparam[4] = 1, omega = dparam[8]; mapping form and the C
    # setter names give the same solve.
    a = fc3d.solve(w, q, mu, solver="NSGS", tol=1e-10, iparam={4: 1}, dparam={8: 1.3})
    b = fc3d.solve(w, q, mu, solver="NSGS", tol=1e-10, **{"iparam[4]": 1, "dparam[8]": 1.3})
    c = fc3d.solve(w, q, mu, solver="NSGS", tol=1e-10, iparam=[(4, 1)], dparam=[(8, 1.3)])
    plain = fc3d.solve(w, q, mu, solver="NSGS", tol=1e-10)
    assert a.converged and a.iterations == b.iterations == c.iterations
    np.testing.assert_array_equal(a.r, b.r)
    assert a.iterations != plain.iterations
    # The local solver by name or id.
    by_name = fc3d.solve(w, q, mu, solver="NSGS", tol=1e-10, local_solver="NSN_GP")
    by_id = fc3d.solve(w, q, mu, solver="NSGS", tol=1e-10, local_solver=551)
    assert by_name.converged and by_name.iterations == by_id.iterations
    np.testing.assert_array_equal(by_name.r, by_id.r)
    # Parameters of the local solver after choosing it (local_iparam[0]: its iteration limit).
    ebp = fc3d.solve(w, q, mu, solver="NSGS", tol=1e-10, local_solver="EBP",
                     local_iparam={0: 50}, local_dparam={0: 1e-14})
    assert ebp.converged
    # Pass-through of the other C setter names.
    same = fc3d.solve(w, q, mu, solver="NSGS", **{"tolerance": 1e-10, "max_iter": 1000})
    assert same.iterations == plain.iterations


def test_zero_contacts():
    """A problem without contacts is solved trivially."""
    res = fc3d.solve(np.zeros((0, 0)), np.zeros(0), np.zeros(0))
    assert res.converged and res.r.shape == (0,) and res.u.shape == (0,)


def test_threads_solve_in_parallel():
    """Independent solves in threads (the library releases the GIL) give the serial results."""
    problems = [random_problem(20, seed=s) for s in range(4)]
    serial = [fc3d.solve(w, q, mu, tol=1e-10).r for w, q, mu in problems]
    results = [None] * len(problems)

    def work(k):
        """Solves problem k in this thread."""
        w, q, mu = problems[k]
        results[k] = fc3d.solve(w, q, mu, tol=1e-10).r

    threads = [threading.Thread(target=work, args=(k,)) for k in range(len(problems))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(serial, results):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("solver, internal", [("PROX", 500), ("TFP", 567), ("PFP", 567)])
def test_internal_solvers(solver, internal):
    """The internal solver of PROX, TFP and PFP is chosen by ``internal_solver``."""
    res = fc3d.solve(np.eye(3), np.array([-1.0, 2.0, 0.0]), np.array([0.5]), solver=solver,
                     tol=1e-10, internal_solver=internal)
    assert res.converged
    np.testing.assert_allclose(res.r, [1.0, -0.5, 0.0], atol=1e-7)


def test_internal_solver_the_solver_cannot_use_is_refused():
    with pytest.raises(fc3d.Fc3dError) as e:
        fc3d.solve(np.eye(3), np.array([-1.0, 2.0, 0.0]), np.array([0.5]), solver="PROX",
                   internal_solver=551)
    assert e.value.code == fc3d.ERR_INVALID_OPTION and "cannot be used" in str(e.value)
