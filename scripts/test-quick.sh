#!/usr/bin/env bash
# The quick tier (docs/testing.md): every crate's Rust tests, as `cargo test` runs them, but the
# three that take most of its time, which the full tier (scripts/test-all.sh, CI) runs:
#   shared_problems_through_the_c_api_in_all_storages   (capi-tests: every shared 3D problem
#                                                        through the C API in four storages)
#   results_are_bitwise_identical_for_1_to_4_threads    (core: threaded NSGS, 1-4 threads, bit
#                                                        for bit on a 6000-contact scene)
#   same_bits_for_every_process_count_and_partition    (fc3d-mpi: mpirun -np 1-4, every partition;
#                                                        minutes when the 2 cores are loaded)
# Together they were 560 of the 860 s of tests in one `cargo test` run on 2 loaded cores.
#
#   bash scripts/test-quick.sh [more arguments for the test binaries]
set -euo pipefail
cd "$(dirname "$0")/.."
exec cargo test --workspace -- \
  --skip shared_problems_through_the_c_api_in_all_storages \
  --skip results_are_bitwise_identical_for_1_to_4_threads \
  --skip same_bits_for_every_process_count_and_partition "$@"
