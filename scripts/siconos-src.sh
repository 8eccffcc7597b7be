#!/usr/bin/env bash
# Prints the directory of Siconos 4.4.0's sources (target/siconos-src/siconos-4.4.0), after
# downloading Debian's orig tarball (checksum pinned: the release of the installed
# libsiconos-numerics) and extracting its numerics/ folder on first use. Read-only reference for
# the scripts that compare fc3d with Siconos (siconos-suite.sh, siconos-names.sh,
# siconos-options.sh): headers Debian does not install, Siconos' own tests.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
TARBALL=siconos_4.4.0+dfsg.orig.tar.xz
SHA256=df9445096559a7352b7a1f16897b4609c26e20caa440ecaf5375b2cdabcb6354
CACHE=$ROOT/target/siconos-src
SRC=$CACHE/siconos-4.4.0
if [ ! -f "$SRC/numerics/numerics_tests.cmake" ]; then
  mkdir -p "$CACHE"
  if [ ! -f "$CACHE/$TARBALL" ] || ! echo "$SHA256  $CACHE/$TARBALL" | sha256sum -c --quiet - 2>/dev/null; then
    echo "== downloading Siconos 4.4.0's sources ($TARBALL)" >&2
    curl -fsSL --retry 3 -o "$CACHE/$TARBALL.part" \
      "http://deb.debian.org/debian/pool/main/s/siconos/$TARBALL"
    mv "$CACHE/$TARBALL.part" "$CACHE/$TARBALL"
  fi
  echo "$SHA256  $CACHE/$TARBALL" | sha256sum -c --quiet - >&2
  tar xJf "$CACHE/$TARBALL" -C "$CACHE" siconos-4.4.0/numerics
  [ -f "$SRC/numerics/numerics_tests.cmake" ] || { echo "siconos-src: extraction failed" >&2; exit 1; }
fi
echo "$SRC"
