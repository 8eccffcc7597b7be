#!/usr/bin/env bash
# Tests the Python package (python/) the way a user installs it:
#
#   bash scripts/test-python.sh [pytest arguments]
#
# builds the native-only C library with cargo, creates a virtual environment in a temporary
# folder, pip-installs numpy, scipy, pytest and ./python into it (from the index pip is configured
# with: needs network access or a mirror), runs python/tests with pytest, then the README's Python
# quickstart as written (with the venv's python first on PATH). The virtual
# environment is removed at the end.
#
# Environment: PYTHON (interpreter, default python3; CPython >= 3.8), FC3D_DATA (the shared
# Siconos problems, default ../shared/data/siconos: the tests needing them are skipped when it is
# absent), FC3D_TEST_KEEP_VENV=1 (keep the virtual environment and print its path).
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
python=${PYTHON:-python3}

command -v "$python" >/dev/null || { echo "test-python: $python not found (set PYTHON)" >&2; exit 1; }
"$python" - <<'EOF' || { echo "test-python: $python is too old: the fc3d package needs CPython >= 3.8" >&2; exit 1; }
import sys
sys.exit(0 if sys.version_info >= (3, 8) else 1)
EOF

echo "== building the native-only C library (cargo)"
# The same command as python/setup.py runs: pip's build below then finds it up to date, and a
# compile error shows here with cargo's own output.
cargo build --release -p fc3d --no-default-features --target-dir target/native

venv=$(mktemp -d "${TMPDIR:-/tmp}/fc3d-python-test.XXXXXX")
if [ "${FC3D_TEST_KEEP_VENV:-0}" = 1 ]; then
  echo "test-python: keeping the virtual environment $venv"
else
  trap 'rm -rf "$venv"' EXIT
fi

echo "== creating a virtual environment with $("$python" --version 2>&1) in $venv"
if ! "$python" -m venv "$venv" 2>"$venv.err"; then
  cat "$venv.err" >&2; rm -f "$venv.err"
  cat >&2 <<EOF
test-python: '$python -m venv' failed. Debian and Ubuntu ship the venv module (with ensurepip)
separately from python3: install it with
    sudo apt-get install python3-venv        (or python3.X-venv for your version)
then run this script again. (Without root: 'pip install --user virtualenv' and re-run; this
script falls back to 'python3 -m virtualenv' when it is available.)
EOF
  if "$python" -m virtualenv --version >/dev/null 2>&1; then
    echo "test-python: using virtualenv instead" >&2
    rm -rf "$venv"
    "$python" -m virtualenv -q "$venv"
  else
    exit 1
  fi
fi
rm -f "$venv.err"
vpython="$venv/bin/python"

echo "== pip install numpy scipy pytest ./python"
export PIP_DISABLE_PIP_VERSION_CHECK=1
"$vpython" -m pip install -q numpy scipy pytest
"$vpython" -m pip install -q ./python
"$vpython" -c 'import fc3d; print("fc3d", fc3d.__version__, "from", fc3d.library_path)'

echo "== pytest python/tests"
# Run from outside the repository so that only the installed package can be imported; no cache
# or bytecode is written into python/.
cd "$venv"
PYTHONDONTWRITEBYTECODE=1 "$vpython" -m pytest -p no:cacheprovider -q "$repo/python/tests" "$@"

echo "== the README's Python quickstart (blocks quickstart.py and run-python, scripts/test-readme.sh)"
mkdir "$venv/readme"
bash "$repo/scripts/test-readme.sh" --print quickstart.py >"$venv/readme/quickstart.py"
run=$(bash "$repo/scripts/test-readme.sh" --print run-python)
(cd "$venv/readme" && PATH="$venv/bin:$PATH" bash -e -c "$run")
