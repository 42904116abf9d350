#!/usr/bin/env bash
# make bench: runs every benchmark program and prints its table. Figures worth
# keeping go to bench/RESULTS.md with the machine and the date.
# Usage: bench.sh BUILD_DIR
set -euo pipefail
build=${1:-build}
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "date:    $(date -u +%Y-%m-%d)"
found=0
for b in "$build"/bench_*; do
  [ -x "$b" ] || continue
  found=1
  echo
  echo "== $(basename "$b")"
  "$b"
done
if [ "$found" -eq 0 ]; then
  echo "bench.sh: no benchmark programs in $build (run make build first)" >&2
  exit 1
fi
