#!/usr/bin/env bash
# A fleet of thousands, simulated, on one coordinator (issue 35, item 12). For each fleet size
# ACTORS/LEARNERS: a fresh dcs-coordinator on loopback (its own data directory, pinned to CPU
# COORDINATOR_CPU) and fleet_benchmark (pinned to SIMULATOR_CPU), which submits a sweep of
# CartPole runs (CONFIG, n_envs so that every actor has a slot: ACTORS / (2 x LEARNERS)) and
# plays the actors and learners over gRPC at the real workers' cadence for WARMUP + SECONDS
# (bench/cluster/fleet_benchmark.cc says what each does and what is measured). Prints the
# table of bench/RESULTS.md, "A fleet on one coordinator", and keeps each size's output.
# Usage: bench/cluster/fleet.sh [ACTORS/LEARNERS ...]   (default 100/10 500/50 1000/100 2000/200
#        4000/400)
#   (BUILD_DIR: build; WARMUP: 20; SECONDS_PER_SIZE: 60; CONFIG:
#    configs/cartpole_length_pool7_static_blind.yaml; COORDINATOR_CPU: 0; SIMULATOR_CPU: 1;
#    COORDINATOR: the dcs-coordinator to measure, default BUILD_DIR's; COORDINATOR_FLAGS: more
#    flags for it; FLEET_FLAGS: for fleet_benchmark)
set -euo pipefail
build="${BUILD_DIR:-build}"
warmup="${WARMUP:-20}"
seconds="${SECONDS_PER_SIZE:-60}"
config="${CONFIG:-configs/cartpole_length_pool7_static_blind.yaml}"
sizes=("$@")
((${#sizes[@]})) || sizes=(100/10 500/50 1000/100 2000/200 4000/400)
dir="$(mktemp -d /tmp/dcs-fleet.XXXXXX)"
coordinator_pid=""
cleanup() {
  if [[ -n "$coordinator_pid" ]]; then
    kill -TERM "$coordinator_pid" 2> /dev/null || true
    wait "$coordinator_pid" 2> /dev/null || true
  fi
  echo "kept in $dir" >&2
}
trap cleanup EXIT

rows=()
for size in "${sizes[@]}"; do
  actors="${size%/*}"
  learners="${size#*/}"
  runs_at_once=$((2 * learners))
  n_envs=$(((actors + runs_at_once - 1) / runs_at_once))
  out="$dir/$actors-$learners"
  mkdir -p "$out"
  # Enough runs for the whole measurement: a run ends after about 150k / (n_envs x 1,400) s.
  {
    echo "name: fleet"
    echo "seeds: $((runs_at_once * 5))"
    echo "observe: [none]"
    sed -e '/^seed:/d' -e '/^observe:/d' -e '/^schedule:/d' -e "s/^n_envs:.*/n_envs: $n_envs/" \
      "$config"
    echo "conditions:"
    echo "  - name: static"
  } > "$out/sweep.yaml"
  taskset -c "${COORDINATOR_CPU:-0}" "${COORDINATOR:-$build/services/dcs-coordinator}" \
    --data-dir "$out/coordinator" --listen 127.0.0.1:0 --metrics-listen 127.0.0.1:0 \
    --port-file "$out/coordinator.ports" ${COORDINATOR_FLAGS:-} > "$out/coordinator.log" 2>&1 &
  coordinator_pid=$!
  until [[ -s "$out/coordinator.ports" ]]; do sleep 0.1; done
  port=$(sed -n 's/^grpc_port: *//p' "$out/coordinator.ports")
  taskset -c "${SIMULATOR_CPU:-1}" "$build/bench/cluster/fleet_benchmark" \
    --coordinator "127.0.0.1:$port" --pid "$coordinator_pid" --sweep-spec "$out/sweep.yaml" \
    --actors "$actors" --learners "$learners" --warmup "$warmup" --seconds "$seconds" \
    ${FLEET_FLAGS:-} | tee "$out/fleet.txt"
  rows+=("$(head -1 "$out/fleet.txt")")
  kill -TERM "$coordinator_pid"
  wait "$coordinator_pid" || true
  coordinator_pid=""
  rm -rf "$out/coordinator"
done

echo
echo "| actors / learners | calls/s | RenewLease p50 ms | p99 ms |" \
     "lease calls p99 ms (renew, release) | long polls' lag p99 ms | failed calls |" \
     "coordinator cores | RSS MiB | peak MiB |" \
     "simulator cores |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
