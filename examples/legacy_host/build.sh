#!/usr/bin/env bash
# Install exic into PREFIX (tools/install.sh: the program, the library, the module files and
# the C header) and build the legacy hosts against that installation into OUT. Used by the test
# suite (test/legacy/test_legacy.f90):
#   examples/legacy_host/build.sh PREFIX OUT
# The fpm command is $EXIC_FPM if set (make test sets it to the project's .venv/bin/fpm),
# else fpm on PATH. The default (debug) profile is used, the one `fpm test` has built.
set -euo pipefail
prefix=$1
out=$2
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
mkdir -p "$prefix" "$out"
prefix=$(cd "$prefix" && pwd)
out=$(cd "$out" && pwd)
"$root/tools/install.sh" "$prefix" > "$out/install.log" 2>&1 || { cat "$out/install.log"; exit 1; }
make -s -C "$here" PREFIX="$prefix" OUT="$out" all
