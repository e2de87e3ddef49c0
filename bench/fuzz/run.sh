#!/usr/bin/env bash
# The fuzzing benchmark of issue 14: each fuzz target of tests/fuzz/ fed a million new inputs
# (after its seeds) under AddressSanitizer and UndefinedBehaviorSanitizer, one target at a time.
# Prints, per target, the inputs run, executions per second, peak RSS and whether anything was
# reported (a crash, leak, sanitizer report or failed check; its input is kept in the work
# directory). Results in bench/RESULTS.md. Needs the fuzz build (make fuzz-build).
#
#   bench/fuzz/run.sh [fuzz build dir (build-fuzz)] [inputs per target (1000000)]
#   FUZZ_MAX_SECONDS=600 bench/fuzz/run.sh   # also stop each target after 10 minutes
#   FUZZ_TARGETS="checkpoint_fuzzer run_store_fuzzer" bench/fuzz/run.sh   # some targets only
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build-fuzz}
runs=${2:-1000000}
max_seconds=${FUZZ_MAX_SECONDS:-0}
targets=${FUZZ_TARGETS:-$(cd "$root/tests/fuzz/corpus" && ls)}
work=$build/bench-fuzz

printf '%-28s %10s %10s %10s %8s  %s\n' target inputs exec/s "peak RSS" seconds reported
status=0
for target in $targets; do
  log=$work/$target.log
  mkdir -p "$work/$target"
  start=$(date +%s)
  "$root/tests/fuzz/fuzz_pass.sh" "$build/tests/fuzz/$target" "$root/tests/fuzz/corpus/$target" \
    "$work/$target" -runs="$runs" -max_total_time="$max_seconds" >"$log" 2>&1
  code=$?
  seconds=$(($(date +%s) - start))
  stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -1; }
  if [ $code -eq 0 ]; then
    reported=nothing
  else
    reported="YES (exit $code): $(grep -m1 -E 'ERROR|runtime error|fuzz check failed' "$log")"
    status=1
  fi
  printf '%-28s %10s %10s %7s MB %8s  %s\n' "$target" "$(stat number_of_executed_units)" \
    "$(stat average_exec_per_sec)" "$(stat peak_rss_mb)" "$seconds" "$reported"
done
exit $status
