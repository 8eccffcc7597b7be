"""Shared fixtures of the fc3d Python tests.

The tests import the *installed* package (`pip install ./python`); the shared Siconos problems
are found through the environment variable FC3D_DATA, by default ``../shared/data/siconos``
relative to the repository root (the parent of python/); tests that need them are skipped when
the folder is absent.
"""

import os
from pathlib import Path

import numpy as np
import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]


def data_dir():
    """The folder of the shared Siconos problems (FC3D_DATA or <repo>/../shared/data/siconos)."""
    return Path(os.environ.get("FC3D_DATA") or REPO_ROOT.parent / "shared" / "data" / "siconos")


@pytest.fixture
def shared_data():
    """The shared data folder; skips the test when it is absent."""
    folder = data_dir()
    if not folder.is_dir():
        pytest.skip("shared problems not found in %s (set FC3D_DATA)" % folder)
    return folder


def random_problem(n_contacts, seed=0):
    """A random well-posed problem: W symmetric positive definite (a Delassus-like
    ``A A^T / n + 0.1 I``), normal free velocities negative (every contact is pressed), mu in
    [0.1, 0.9]. NSGS solves it to 1e-10 in a few dozen sweeps."""
    rng = np.random.default_rng(seed)
    n = 3 * n_contacts
    a = rng.standard_normal((n, n + 6))
    w = a @ a.T / n + 0.1 * np.eye(n)
    q = rng.standard_normal(n)
    q[0::3] = -np.abs(q[0::3]) - 0.1
    mu = rng.uniform(0.1, 0.9, n_contacts)
    return w, q, mu


@pytest.fixture
def problem30():
    """A random problem with 30 contacts (dense W, q, mu)."""
    return random_problem(30, seed=1)
