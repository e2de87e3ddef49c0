#!/usr/bin/env bash
# GetRun's p50 and p99 on a fresh dcs-coordinator (loopback, its own data directory), quiet and
# while clients submit configs/quickstart.yaml (18 runs) back to back
# (bench/cluster/getrun_under_commits.cc).
# Usage: bench/cluster/getrun_under_commits.sh [DRIVER ARGS: --seconds S --writers W]
#   BUILD_DIR: the build whose driver runs (default build)
#   COORDINATOR: the dcs-coordinator measured (default: BUILD_DIR's), e.g. an older build's
set -euo pipefail
build="${BUILD_DIR:-build}"
coordinator="${COORDINATOR:-$build/services/dcs-coordinator}"
data="$(mktemp -d)"
"$coordinator" --listen=127.0.0.1:0 --metrics-listen=127.0.0.1:0 --data-dir="$data/store" \
  --port-file="$data/ports" > "$data/log" 2>&1 &
pid=$!
trap 'kill "$pid"; wait "$pid" || true; rm -rf "$data"' EXIT
for _ in $(seq 100); do [ -s "$data/ports" ] && break; sleep 0.1; done
port=$(sed -n "s/^grpc_port: *//p" "$data/ports")
"$build/bench/cluster/getrun_under_commits" "127.0.0.1:$port" configs/quickstart.yaml "$@"
