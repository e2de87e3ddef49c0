#!/usr/bin/env bash
# Trains one config with several seeds, a few at a time, then prints their scores and the IQM
# [Q1, Q3] across them (dcs summarize): how a row of the paper's tables is reproduced, and how
# bench/RESULTS.md's training figures were made.
#
#   bench/learner/train_seeds.sh CONFIG SEEDS [JOBS] [OUT]
#     CONFIG  a run config (configs/*.yaml)
#     SEEDS   seeds 0 .. SEEDS-1
#     JOBS    runs at a time (default: the number of cores; each run uses one)
#     OUT     where the runs go (default: bench-runs/<config name>); must not hold them yet
# Needs a build (build/services/dcs, as `make build` makes it). Each run's wall time goes to
# OUT/seconds.csv.
set -euo pipefail

config=${1:?usage: train_seeds.sh CONFIG SEEDS [JOBS] [OUT]}
seeds=${2:?usage: train_seeds.sh CONFIG SEEDS [JOBS] [OUT]}
jobs=${3:-$(nproc)}
out=${4:-bench-runs/$(basename "${config}" .yaml)}
dcs=${DCS:-build/services/dcs}

mkdir -p "${out}"
echo "seed,seconds" > "${out}/seconds.csv"
export config out dcs
seq 0 $((seeds - 1)) | xargs -P "${jobs}" -I{} bash -c '
  start=${EPOCHREALTIME}
  "${dcs}" train "${config}" --seed {} --out "${out}/seed{}" > /dev/null 2> "${out}/seed{}.log"
  awk -v s="${start}" -v e="${EPOCHREALTIME}" "BEGIN { printf \"{},%.2f\n\", e - s }" >> "${out}/seconds.csv"'
"${dcs}" summarize "${out}"/seed*/
