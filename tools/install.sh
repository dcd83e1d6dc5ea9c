#!/usr/bin/env bash
# Install exic: the `exic` program into PREFIX/bin, libexic.a into PREFIX/lib, the library's
# module files (exic_*.mod) and the C header exic_contact.h into PREFIX/include. Nothing else:
# `fpm install` would also install the benchmark programs and their module, so fpm installs into
# a staging directory (build/install-stage) and only what belongs is copied from there.
#
#   tools/install.sh PREFIX [fpm options...]     e.g. --profile release --flag "..."
#
# `make install PREFIX=dir` runs it with the release options; examples/legacy_host/build.sh
# (the legacy API tests) with none (fpm's debug profile, the one `fpm test` has built).
# The fpm command is $EXIC_FPM if set, else fpm on PATH.
set -euo pipefail
if [ $# -lt 1 ]; then
  echo "usage: tools/install.sh PREFIX [fpm options...]" >&2
  exit 2
fi
prefix=$1
shift
fpm=${EXIC_FPM:-fpm}
root=$(cd "$(dirname "$0")/.." && pwd)
stage=$root/build/install-stage
cd "$root"
rm -rf "$stage"
mkdir -p "$stage"
if ! "$fpm" install --prefix "$stage" "$@" > "$stage.log" 2>&1; then
  cat "$stage.log" >&2
  echo "install: fpm install failed (log: $stage.log)" >&2
  exit 1
fi
for f in "$stage/bin/exic" "$stage/lib/libexic.a"; do
  [ -f "$f" ] || { echo "install: fpm did not produce $f" >&2; exit 1; }
done
mkdir -p "$prefix/bin" "$prefix/lib" "$prefix/include"
install -m 755 "$stage/bin/exic" "$prefix/bin/"
install -m 644 "$stage/lib/libexic.a" "$prefix/lib/"
install -m 644 "$stage"/include/exic_*.mod "$prefix/include/"
install -m 644 include/exic_contact.h "$prefix/include/"
echo "install: exic, libexic.a, $(ls "$stage"/include/exic_*.mod | wc -l) module files and exic_contact.h in $prefix"
