#!/usr/bin/env bash
# N runs of one config trained at once on a local cluster (`dcs up`: a learner, an actor per
# core), each submitted and followed by its own `dcs train --cluster`. Prints the wall seconds
# from the first submission to the last run's end, the environment steps of all runs, and their
# aggregate steps per second (updates and evaluations included; the cluster's start-up not),
# and how busy the cores were: the CPU seconds of the cluster's processes (their
# process_cpu_seconds_total) over wall seconds times cores.
# Usage: bench/cluster/concurrent_runs.sh [N] [CONFIG]   (BUILD_DIR: default build)
set -euo pipefail
dcs="${BUILD_DIR:-build}/services/dcs"
runs="${1:-16}"
config="${2:-configs/cartpole_length_pool7_static_blind.yaml}"
data="$(mktemp -d)"
"$dcs" up -d --data-dir "$data" > /dev/null
trap '"$dcs" down --data-dir "$data" > /dev/null; rm -rf "$data"; kill $extra 2> /dev/null || true' EXIT
extra=""
# EXTRA_LEARNERS more learners beside the cluster's one (to try other shapes of the cluster).
for i in $(seq 1 "${EXTRA_LEARNERS:-0}"); do
  coordinator=$(sed -n 's/^coordinator: *//p' "$data/cluster.yaml")
  "$(dirname "$dcs")/dcs-learner" --coordinator "$coordinator" > "$data/logs/extra-$i.log" 2>&1 &
  extra="$extra $!"
done

start=$(date +%s.%N)
clients=()
for seed in $(seq 0 $((runs - 1))); do
  "$dcs" train --cluster --data-dir "$data" --config "$config" --seed "$seed" \
    --out "$data/out/$seed" > /dev/null 2>&1 &
  clients+=($!)
done
wait "${clients[@]}"
end=$(date +%s.%N)

steps=$("$dcs" runs --data-dir "$data" -o json |
        python3 -c 'import json, sys; print(sum(int(r["progress"]["timesteps"])
                    for r in json.load(sys.stdin)["runs"] if r["state"] == "RUN_STATE_COMPLETED"))')
cpu=0
for metrics in $(sed -n 's/^ *metrics: *//p' "$data/cluster.yaml"); do
  seconds=$(curl -s "http://$metrics/metrics" | sed -n 's/^process_cpu_seconds_total //p')
  cpu=$(python3 -c "print($cpu + ${seconds:-0})")
done
python3 - "$runs" "$start" "$end" "$steps" "$cpu" "$(nproc)" <<'PY'
import sys
runs, start, end, steps, cpu, cores = (int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]),
                                       int(sys.argv[4]), float(sys.argv[5]), int(sys.argv[6]))
wall = end - start
print(f"runs {runs}  wall_s {wall:.1f}  steps {steps}  steps_per_s {steps / wall:.0f}  "
      f"cluster_cpu_s {cpu:.0f}  busy {cpu / (wall * cores):.2f}")
PY
