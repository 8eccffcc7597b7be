#!/usr/bin/env bash
# The allocation tests under an address-space limit (issue 13, item 3; issue 29, item 6): every
# test of the test binaries below runs in its own process under `ulimit -v` (1 GiB unless
# FC3D_MEMORY_LIMIT_KIB says otherwise), the ignored `under_memory_limit_*` tests included
# (endless valid values from streams and pipes, which must end in Fc3dError::OutOfMemory /
# FC3D_ERR_OUT_OF_MEMORY). The tests of capi/tests/huge_problem.rs hold a host's arrays for 10^8
# contacts (8 GiB of address space, never touched) and lower the limit themselves to what they
# hold plus a headroom for fc3d: they run under 12 GiB (FC3D_HOST_MEMORY_LIMIT_KIB), with one
# malloc arena (glibc's per-thread arenas reserve 64 MiB of address space each, which would
# serve allocations past the limit they set). A test process killed by a signal (SIGABRT from a
# failed infallible allocation, SIGKILL, SIGSEGV) or failing makes the script fail, naming it.
#
#   bash scripts/test-memory-limit.sh            # from the repository root
#
# The binaries are built first without the limit (rustc needs more than 1 GiB of address space).
set -euo pipefail
cd "$(dirname "$0")/.."

LIMIT_KIB=${FC3D_MEMORY_LIMIT_KIB:-1048576}
HOST_LIMIT_KIB=${FC3D_HOST_MEMORY_LIMIT_KIB:-12582912}
# The FCLIB reader's case needs libhdf5 (as `cargo test --features fc3d-core/fclib` does).
CORE_FEATURES=""
if pkg-config --exists hdf5 2>/dev/null; then
    CORE_FEATURES="--features fclib"
fi
# Test binaries: limit (KiB), malloc tunables, package, test target, cargo options.
TARGETS=(
    "$LIMIT_KIB - fc3d-core reader_limits $CORE_FEATURES"
    "$LIMIT_KIB - fc3d file_limits"
    "$HOST_LIMIT_KIB glibc.malloc.arena_max=1 fc3d huge_problem"
)

binaries=()
limits=()
tunables=()
for target in "${TARGETS[@]}"; do
    read -r limit tunable package test options <<<"$target"
    limits+=("$limit")
    tunables+=("$tunable")
    echo "== building $package --test $test $options"
    # shellcheck disable=SC2086
    exe=$(cargo test -p "$package" --test "$test" $options --no-run --message-format=json 2>/dev/null |
        python3 -c '
import json, sys
for line in sys.stdin:
    try:
        m = json.loads(line)
    except ValueError:
        continue
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["target"]["name"] == sys.argv[1]:
        print(m["executable"])
' "$test" | tail -n 1)
    if [ -z "$exe" ]; then
        echo "cannot build $package --test $test:" >&2
        # shellcheck disable=SC2086
        cargo test -p "$package" --test "$test" $options --no-run >&2 || true
        exit 1
    fi
    binaries+=("$exe")
done

failed=0
ran=0
for k in "${!binaries[@]}"; do
    exe=${binaries[$k]}
    limit=${limits[$k]}
    tunable=${tunables[$k]}
    [ "$tunable" != "-" ] || tunable=""
    tests=$("$exe" --list --include-ignored 2>/dev/null | sed -n 's/: test$//p')
    for name in $tests; do
        log=$(mktemp)
        set +e
        (
            ulimit -v "$limit"
            GLIBC_TUNABLES=$tunable exec "$exe" --exact "$name" --include-ignored --test-threads=1 --nocapture
        ) >"$log" 2>&1
        rc=$?
        set -e
        ran=$((ran + 1))
        if [ "$rc" -gt 128 ]; then
            echo "KILLED by signal $((rc - 128)): $(basename "$exe") $name" >&2
            tail -n 20 "$log" >&2
            failed=$((failed + 1))
        elif [ "$rc" -ne 0 ]; then
            echo "FAILED (exit $rc): $(basename "$exe") $name" >&2
            tail -n 30 "$log" >&2
            failed=$((failed + 1))
        else
            oom=$(grep -c "out of memory at" "$log" || true)
            if [ "$oom" -gt 0 ]; then
                echo "ok: $name ($oom out-of-memory errors, as expected)"
            else
                echo "ok: $name"
            fi
        fi
        rm -f "$log"
    done
done

echo "== $ran tests under ulimit -v ($LIMIT_KIB KiB, $HOST_LIMIT_KIB KiB for huge_problem): $failed failed"
[ "$failed" -eq 0 ]
