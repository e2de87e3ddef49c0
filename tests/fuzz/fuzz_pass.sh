#!/usr/bin/env bash
# One pass of a libFuzzer target: its committed seed corpus first (each seed must pass, as a
# regression test), then new inputs for as long as the libFuzzer flags given allow. New inputs
# go to <work dir>/corpus and a crashing input to <work dir>/; the committed corpus is only read.
# Exits with the fuzzer's status: 0 if nothing was reported.
#
#   fuzz_pass.sh <fuzzer> <seed corpus dir> <work dir> [libFuzzer flags, e.g. -max_total_time=20]
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 <fuzzer> <seed corpus dir> <work dir> [libFuzzer flags...]" >&2
  exit 2
fi
fuzzer=$1 seeds=$2 work=$3
shift 3
rm -rf "$work/corpus"
mkdir -p "$work/corpus"
# UBSan's reports with their stack; every input bounded in time (a hang is a finding too).
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
exec "$fuzzer" -artifact_prefix="$work/" -timeout=25 -print_final_stats=1 "$@" \
  "$work/corpus" "$seeds"
