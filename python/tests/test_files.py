"""fc3d.read_problem on the shared Siconos problems, and the example script."""

import subprocess
import sys

import numpy as np
import pytest

import fc3d
from conftest import REPO_ROOT

try:
    import scipy.sparse as scipy_sparse
except ImportError:
    scipy_sparse = None

# Small shared problems both NSGS and NSN_AC solve to 1e-8 in milliseconds: a rover (4
# contacts), an object on a plane (23), Confeti (107, sparse-block storage in the file).
FILES = ["Rover1039.dat", "OneObject-i1028-138.hdf5.dat", "Confeti-ex13-Fc3D-SBM.dat"]


@pytest.mark.parametrize("name", FILES)
def test_read_problem(shared_data, name):
    """read_problem gives W, q, mu of consistent sizes, read-only."""
    problem = fc3d.read_problem(shared_data / name)
    nc = problem.n_contacts
    n = 3 * nc
    assert nc > 0 and problem.W.shape == (n, n)
    assert problem.q.shape == (n,) and problem.mu.shape == (nc,)
    assert np.all(problem.mu >= 0) and np.all(np.isfinite(problem.q))
    if scipy_sparse is not None:
        assert isinstance(problem.W, scipy_sparse.csr_matrix)
        assert problem.W.nnz == problem.nnz
    with pytest.raises(ValueError):
        problem.q[0] = 1.0  # read-only: the library's copy would not change
    assert str(shared_data / name) in repr(problem)


@pytest.mark.parametrize("name", FILES)
@pytest.mark.parametrize("solver", ["NSGS", "NSN_AC"])
def test_solve_shared_problem(shared_data, name, solver):
    """NSGS and NSN_AC solve shared problems to 1e-8, from the handle and from the arrays."""
    problem = fc3d.read_problem(shared_data / name)
    res = fc3d.solve(problem, solver=solver, tol=1e-8, max_iter=100000, time_budget=20)
    assert res.converged, res
    assert res.error <= 1e-8
    # u = W r + q, with W as read_problem gives it.
    np.testing.assert_allclose(res.u, problem.W @ res.r + problem.q, rtol=1e-9, atol=1e-9)
    # The arrays of the problem give the same problem (here in compressed rows).
    again = fc3d.solve(problem.W, problem.q, problem.mu, solver=solver, tol=1e-8,
                       max_iter=100000, time_budget=20)
    assert again.converged and again.error <= 1e-8
    scale = max(1.0, np.abs(res.r).max())
    np.testing.assert_allclose(again.r, res.r, rtol=1e-6, atol=1e-8 * scale)
    # The method is the same call.
    same = problem.solve(solver=solver, tol=1e-8, max_iter=100000, time_budget=20)
    assert same.iterations == res.iterations
    np.testing.assert_array_equal(same.r, res.r)


def test_read_problem_without_scipy(shared_data, monkeypatch):
    """Without scipy, W is a dense numpy array with the same entries."""
    from fc3d import _api

    path = shared_data / "Rover1039.dat"
    with_scipy = fc3d.read_problem(path)
    monkeypatch.setattr(_api, "_sparse", None)
    dense = fc3d.read_problem(path)
    assert isinstance(dense.W, np.ndarray) and dense.W.shape == with_scipy.W.shape
    expected = with_scipy.W.toarray() if scipy_sparse is not None else with_scipy.W
    np.testing.assert_array_equal(dense.W, expected)
    res = fc3d.solve(dense.W, dense.q, dense.mu, tol=1e-8)
    assert res.converged


def test_closed_problem(shared_data):
    """A closed problem cannot be solved; q and mu cannot be given with a problem."""
    with fc3d.read_problem(shared_data / "Rover1039.dat") as problem:
        assert problem.solve(tol=1e-8).converged
    with pytest.raises(fc3d.Fc3dError, match="closed"):
        fc3d.solve(problem)
    with pytest.raises(TypeError):
        fc3d.solve(fc3d.read_problem(shared_data / "Rover1039.dat"), np.zeros(12), np.zeros(4))


def test_read_errors(tmp_path):
    """A missing file raises ERR_IO, a malformed one ERR_PARSE, both naming the file."""
    with pytest.raises(fc3d.Fc3dError) as info:
        fc3d.read_problem(tmp_path / "missing.dat")
    assert info.value.code == fc3d.ERR_IO and "missing.dat" in info.value.message
    bad = tmp_path / "bad.dat"
    bad.write_text("3\n2\nnot a number\n")
    with pytest.raises(fc3d.Fc3dError) as info:
        fc3d.read_problem(bad)
    assert info.value.code == fc3d.ERR_PARSE and "bad.dat" in info.value.message


def test_example_script(shared_data):
    """examples/solve_file.py solves a shared problem with two solvers."""
    script = REPO_ROOT / "python" / "examples" / "solve_file.py"
    out = subprocess.run(
        [sys.executable, str(script), str(shared_data / "Rover1039.dat"), "--solver",
         "NSGS,NSN-AC", "--tol", "1e-8"],
        capture_output=True, text=True, timeout=120,
    )
    assert out.returncode == 0, out.stdout + out.stderr
    assert out.stdout.count("converged") == 2 and "NSN_AC" in out.stdout
