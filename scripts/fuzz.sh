#!/usr/bin/env bash
# Runs every libFuzzer harness of tests/fuzz for SECONDS each (make fuzz).
#   scripts/fuzz.sh BUILD_DIR SECONDS [TARGET...]   (targets: scene ply obj table grid pbrt fem_cache)
# Each target keeps a working corpus in BUILD_DIR/fuzz/corpus/TARGET, seeded
# from the bundled files (scenes/*.json, tests/fuzz/corpus/TARGET); inputs that
# crash, leak, run longer than 60 s (far more than any seed takes, even on a
# loaded machine) or allocate more than 1 GB are saved under
# BUILD_DIR/fuzz/artifacts/TARGET and make the script fail. A saved input
# becomes a regression test by copying it to tests/fuzz/regressions/TARGET.
# Each harness is one process on one core; FUZZ_JOBS of them (default: the
# number of cores) run at a time.
set -euo pipefail

build=$1
seconds=$2
shift 2
targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then
  targets=(scene ply obj table grid pbrt fem_cache)
fi
src=$(cd "$(dirname "$0")/.." && pwd)
work="$build/fuzz"

export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
export LSAN_OPTIONS=suppressions=$src/scripts/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Scenes name their meshes relative to this directory (the PLY and OBJ seeds).
mkdir -p "$work/meshes"
cp "$src"/tests/fuzz/corpus/ply/* "$src"/tests/fuzz/corpus/obj/* "$work/meshes/"
export SUBSURF_FUZZ_BASE_DIR=$work/meshes
export OMP_NUM_THREADS=1
# Each input goes through a file: keep it in memory when there is a tmpfs.
if [ -z "${TMPDIR:-}" ] && [ -w /dev/shm ]; then
  export TMPDIR=/dev/shm
fi

# Fuzzes target $1 for $seconds; prints one line, returns 1 on a failure.
fuzz_one() {
  local t=$1
  local corpus="$work/corpus/$t" artifacts="$work/artifacts/$t" log="$work/$t.log"
  mkdir -p "$corpus" "$artifacts"
  local seeds=("$src/tests/fuzz/corpus/$t")
  if [ "$t" = scene ] || [ "$t" = pbrt ]; then
    seeds+=("$src/scenes")
  fi
  if [ -d "$src/tests/fuzz/regressions/$t" ]; then
    seeds+=("$src/tests/fuzz/regressions/$t")
  fi
  if "$build/fuzz_$t" "$corpus" "${seeds[@]}" -max_total_time="$seconds" -timeout=60 \
    -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" >"$log" 2>&1; then
    local runs
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    echo "fuzz_$t: ${runs:-?} inputs in ${seconds} s, no failure (corpus $(ls "$corpus" | wc -l))"
  else
    {
      echo "fuzz_$t: FAILED, see $log; inputs kept in $artifacts:"
      grep -E "^(==[0-9]+==ERROR|SUMMARY)" "$log" | head -3 || true
      ls "$artifacts"
    } >&2
    return 1
  fi
}

jobs=${FUZZ_JOBS:-$(nproc)}
failed=0
running=0
for t in "${targets[@]}"; do
  if [ "$running" -ge "$jobs" ]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
  fuzz_one "$t" &
  running=$((running + 1))
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=1
  running=$((running - 1))
done
exit "$failed"
