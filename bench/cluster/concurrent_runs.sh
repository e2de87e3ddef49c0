#!/usr/bin/env bash
# N runs of one config trained at once on a local cluster (`dcs up`: a learner, an actor per
# core), each submitted and followed by its own `dcs train --cluster`. Prints the wall seconds
# from the first submission to the last run's end, the environment steps of all runs, and their
# aggregate steps per second (updates and evaluations included; the cluster's start-up not),
# and how busy the cores were: the CPU seconds of the cluster's processes (their
# process_cpu_seconds_total, also printed per process) and of the clients, over wall seconds
# times cores.
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
clients_cpu_before=$(awk '{print $14 + $15 + $16 + $17}' /proc/$$/stat)
clients=()
for seed in $(seq 0 $((runs - 1))); do
  "$dcs" train --cluster --data-dir "$data" --config "$config" --seed "$seed" \
    --out "$data/out/$seed" > /dev/null 2>&1 &
  clients+=($!)
done
wait "${clients[@]}"
end=$(date +%s.%N)
# The clients' CPU: this shell's reaped children (cutime + cstime), in clock ticks.
clients_cpu=$(awk -v before="$clients_cpu_before" -v hz="$(getconf CLK_TCK)" \
              '{print ($14 + $15 + $16 + $17 - before) / hz}' /proc/$$/stat)

steps=$("$dcs" runs --data-dir "$data" -o json |
        python3 -c 'import json, sys; print(sum(int(r["progress"]["timesteps"])
                    for r in json.load(sys.stdin)["runs"] if r["state"] == "completed"))')
cpu=0
per_process=""
for process in $(sed -n 's/^ *- name: *//p' "$data/cluster.yaml"); do
  metrics=$(sed -n "/name: $process\$/,/metrics:/s/^ *metrics: *//p" "$data/cluster.yaml")
  seconds=$(curl -s "http://$metrics/metrics" | sed -n 's/^process_cpu_seconds_total //p')
  cpu=$(python3 -c "print($cpu + ${seconds:-0})")
  per_process="$per_process $process=$(printf "%.1f" "${seconds:-0}")"
done
python3 - "$runs" "$start" "$end" "$steps" "$cpu" "$clients_cpu" "$(nproc)" "$per_process" <<'PY'
import sys
runs, start, end, steps, cpu, clients, cores = (
    int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]),
    float(sys.argv[5]), float(sys.argv[6]), int(sys.argv[7]))
wall = end - start
print(f"runs {runs}  wall_s {wall:.1f}  steps {steps}  steps_per_s {steps / wall:.0f}  "
      f"cluster_cpu_s {cpu:.0f} ({sys.argv[8].strip()})  clients_cpu_s {clients:.0f}  "
      f"busy {(cpu + clients) / (wall * cores):.2f}")
PY
