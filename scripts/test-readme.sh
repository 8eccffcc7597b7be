#!/usr/bin/env bash
# The README's examples, run as written:
#
#   bash scripts/test-readme.sh PREFIX           (PREFIX from scripts/install.sh --prefix PREFIX)
#   bash scripts/test-readme.sh --print TAG      (prints the README's blocks marked TAG)
#
# A block of README.md is marked by an HTML comment on the line before its opening fence:
#   <!-- test: FILE -->        the block is saved as FILE in a scratch folder;
#   <!-- test: run -->         the block (shell) is run in that folder with `bash -e`, after the
#                              files, with PREFIX, PKG_CONFIG_PATH and LD_LIBRARY_PATH set to the
#                              installed prefix as the README's Install section sets them;
#   <!-- test: run-python -->  the same for the Python quickstart, run by scripts/test-python.sh
#                              in its virtual environment (where `pip install ./python` was done);
#   <!-- test: in-tree -->     run from the repository root with neither variable set, from a
#                              clean state of ./local (the README's in-tree prefix, ignored by
#                              git: an existing ./local is moved aside and put back afterwards).
# The Rust quickstart is a doctest (core/src/lib.rs includes README.md). The Siconos drop-in
# program is also built against the installed Siconos 4.4, when present, and must print the same
# first line with both libraries.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
README=$ROOT/README.md

# Prints the blocks marked `<!-- test: $1 -->`, one after the other (each followed by a NUL
# character when $2 is "nul").
blocks() {
  awk -v tag="$1" -v nul="${2:-}" '
    $0 == "<!-- test: " tag " -->" { armed = 1; next }
    armed && /^```/ { armed = 0; inside = 1; found++; next }
    inside && /^```$/ { inside = 0; if (nul == "nul") printf "%c", 0; next }
    inside { print }
    { armed = 0 }
    END { if (!found) { print "test-readme: no block marked \"" tag "\" in README.md" > "/dev/stderr"; exit 1 } }
  ' "$README"
}

# The tags of the README's marked blocks, in order of appearance.
tags() {
  sed -n 's/^<!-- test: \(.*\) -->$/\1/p' "$README"
}

if [ "${1:-}" = --print ]; then
  [ $# -eq 2 ] || { echo "usage: bash scripts/test-readme.sh --print TAG" >&2; exit 2; }
  blocks "$2"
  exit 0
fi
[ $# -eq 1 ] || { echo "usage: bash scripts/test-readme.sh PREFIX" >&2; exit 2; }
PREFIX=$(cd "$1" && pwd)

WORK=$(mktemp -d)
moved_local=""
cleanup() {
  rm -rf "$WORK" "$ROOT/local"
  [ -z "$moved_local" ] || mv "$moved_local" "$ROOT/local"
}
trap cleanup EXIT

echo "== the README's quickstarts, built and run against $PREFIX"
for tag in $(tags); do
  case "$tag" in
    run | run-python | in-tree) ;;
    *) blocks "$tag" >"$WORK/$tag"; echo "   $tag ($(wc -l <"$WORK/$tag") lines)" ;;
  esac
done
n=0
while IFS= read -r -d '' script; do
  n=$((n + 1))
  script=${script%$'\n'}
  echo "-- run block $n:"
  sed 's/^/   $ /' <<<"$script"
  (cd "$WORK" && PREFIX=$PREFIX PKG_CONFIG_PATH=$PREFIX/lib/pkgconfig LD_LIBRARY_PATH=$PREFIX/lib \
    bash -e -c "$script") | sed 's/^/   /'
done < <(blocks run nul)
[ "$n" -ge 3 ] || { echo "test-readme: expected the C, native C and Fortran run blocks, found $n" >&2; exit 1; }

if [ -f /usr/include/siconos/numerics/FrictionContactProblem.h ]; then
  echo "== the drop-in program against the installed Siconos 4.4"
  (cd "$WORK" && cc -std=c99 dropin.c -I/usr/include/siconos/numerics -I/usr/include/siconos \
    -lsiconos_numerics -lm -o dropin_siconos)
  ours=$(cd "$WORK" && LD_LIBRARY_PATH=$PREFIX/lib ./dropin | head -1)
  theirs=$(cd "$WORK" && ./dropin_siconos | head -1)
  echo "   fc3d:    $ours"
  echo "   Siconos: $theirs"
  [ "$ours" = "$theirs" ] || { echo "test-readme: the drop-in program differs between fc3d and Siconos" >&2; exit 1; }
else
  echo "note: Siconos 4.4 is not installed; the drop-in program is built against fc3d only"
fi

echo "== the README's in-tree example, from the repository root without ./local"
if [ -e "$ROOT/local" ]; then
  moved_local=$(mktemp -d "$ROOT/local.moved-aside.XXXXXX")
  rmdir "$moved_local"
  mv "$ROOT/local" "$moved_local"
  echo "   (./local moved aside to $moved_local until the end)"
fi
script=$(blocks in-tree)
sed 's/^/   $ /' <<<"$script"
env -u PKG_CONFIG_PATH -u LD_LIBRARY_PATH bash -e -c "$script" >"$WORK/in-tree.log" 2>&1 || {
  cat "$WORK/in-tree.log"; echo "test-readme: the in-tree example failed" >&2; exit 1; }
grep -v '^ *Compiling \|^ *Finished ' "$WORK/in-tree.log" | sed 's/^/   /' || true
# The program runs without any environment: its rpath finds the SONAME link the install made.
# (ldd's output is taken whole first: grep -q stopping early would end ldd by SIGPIPE, a failure
# under pipefail.)
loaded=$(env -u LD_LIBRARY_PATH ldd "$ROOT/local/stack")
grep -q "libfc3d.so.0 => $ROOT/local/lib/" <<<"$loaded" || {
  echo "test-readme: local/stack does not load local/lib/libfc3d.so.0:" >&2; echo "$loaded" >&2; exit 1; }
echo "== README examples: all passed"
