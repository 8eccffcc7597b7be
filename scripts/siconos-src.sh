#!/usr/bin/env bash
# Prints the directory of Siconos 4.4.0's sources (target/siconos-src/siconos-4.4.0). On first use
# it takes Debian's source package `siconos` at the version of the installed libsiconos-numerics
# (4.4.0+dfsg-2) with `apt-get source --download-only`, checks the orig tarball against a pinned
# checksum and extracts its numerics/ folder. Read-only reference for the scripts that compare
# fc3d with Siconos (siconos-suite.sh, siconos-names.sh, siconos-options.sh): headers Debian does
# not install, Siconos' own tests.
#
# The deb-src entries are made from the machine's own apt sources (every `deb` entry of
# /etc/apt/sources.list and /etc/apt/sources.list.d/*.list / *.sources, turned into `deb-src`),
# in an apt configuration private to this script under target/siconos-src/apt: the system's
# sources, package lists and caches are not touched. Works as root (CI) or as a user who can
# reach the network; needs apt-get and tar with xz.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PACKAGE=siconos
VERSION=4.4.0+dfsg-2
TARBALL=siconos_4.4.0+dfsg.orig.tar.xz
SHA256=df9445096559a7352b7a1f16897b4609c26e20caa440ecaf5375b2cdabcb6354
CACHE=$ROOT/target/siconos-src
# The apt configuration read (another folder only to test the derivation).
APT_ETC=${SICONOS_SRC_APT_ETC:-/etc/apt}
SRC=$CACHE/siconos-4.4.0

tarball_ok() {
  [ -f "$CACHE/$TARBALL" ] && echo "$SHA256  $CACHE/$TARBALL" | sha256sum -c --quiet - >/dev/null 2>&1
}

# Writes deb-src entries for every deb entry of the system's sources into $1 (a sources.list.d
# folder): one-line .list entries as one-line entries, deb822 .sources stanzas as stanzas.
derive_deb_src() {
  local parts=$1 f n=0
  for f in "$APT_ETC/sources.list" "$APT_ETC"/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    n=$((n + 1))
    sed -n -E 's/^[[:space:]]*deb([[:space:]])/deb-src\1/p' "$f" >"$parts/system-$n.list"
  done
  for f in "$APT_ETC"/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    n=$((n + 1))
    # Stanzas are separated by blank lines; keep those whose Types include deb (and not
    # Enabled: no), with Types rewritten to deb-src.
    awk 'function flush() {
           if (types ~ /(^|[[:space:]])deb([[:space:]]|$)/ && !disabled) {
             print "Types: deb-src"; printf "%s", body; print ""
           }
           types = ""; body = ""; disabled = 0
         }
         /^[[:space:]]*$/ { flush(); next }
         /^#/ { next }
         tolower($1) == "types:" { sub(/^[^:]*:[[:space:]]*/, ""); types = $0; next }
         tolower($1) == "enabled:" && tolower($2) == "no" { disabled = 1 }
         { body = body $0 "\n" }
         END { flush() }' "$f" >"$parts/system-$n.sources"
  done
  grep -q -E '^(deb-src|Types: deb-src)' "$parts"/* 2>/dev/null || {
    echo "siconos-src: no deb entry in $APT_ETC/sources.list or $APT_ETC/sources.list.d/ to derive deb-src from" >&2
    exit 1
  }
}

fetch_tarball() {
  local apt=$CACHE/apt
  rm -rf "$apt"
  mkdir -p "$apt/parts" "$apt/lists/partial" "$apt/cache/archives/partial" "$apt/download"
  : >"$apt/sources.list"
  derive_deb_src "$apt/parts"
  local opts=(
    -o "Dir::Etc::SourceList=$apt/sources.list"
    -o "Dir::Etc::SourceParts=$apt/parts"
    -o "Dir::State::Lists=$apt/lists"
    -o "Dir::Cache=$apt/cache"
    -o "Dir::Cache::pkgcache=" -o "Dir::Cache::srcpkgcache="
    -o "APT::Sandbox::User=$(id -un)"
  )
  echo "== apt-get source --download-only $PACKAGE=$VERSION (deb-src from the machine's apt sources)" >&2
  apt-get "${opts[@]}" -q update >&2
  (cd "$apt/download" && apt-get "${opts[@]}" -q source --download-only "$PACKAGE=$VERSION" >&2)
  [ -f "$apt/download/$TARBALL" ] || { echo "siconos-src: apt-get source gave no $TARBALL" >&2; exit 1; }
  mv "$apt/download/$TARBALL" "$CACHE/$TARBALL"
  rm -rf "$apt"
}

if [ ! -f "$SRC/numerics/numerics_tests.cmake" ]; then
  mkdir -p "$CACHE"
  # Test programs may ask for the sources at the same time: one fetches, the others wait.
  exec 9>"$CACHE/.lock"
  flock 9
fi
if [ ! -f "$SRC/numerics/numerics_tests.cmake" ]; then
  tarball_ok || fetch_tarball
  echo "$SHA256  $CACHE/$TARBALL" | sha256sum -c --quiet - >&2
  # Extracted aside and moved in whole, so a reader never sees a half-extracted tree.
  rm -rf "$CACHE/extracting" "$SRC"
  mkdir -p "$CACHE/extracting"
  tar xJf "$CACHE/$TARBALL" -C "$CACHE/extracting" siconos-4.4.0/numerics
  [ -f "$CACHE/extracting/siconos-4.4.0/numerics/numerics_tests.cmake" ] || {
    echo "siconos-src: extraction failed" >&2; exit 1; }
  mv "$CACHE/extracting/siconos-4.4.0" "$SRC"
  rmdir "$CACHE/extracting"
fi
echo "$SRC"
