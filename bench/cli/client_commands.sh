#!/usr/bin/env bash
# How long each `dcs` command that does not train takes, start to exit, against a local cluster
# (`dcs up`) holding one finished sweep: a small one (2 conditions x 2 modes x 2 seeds of 2048
# CartPole steps), or, with SWEEP_DATA_DIR and SWEEP, a cluster already up with a sweep of
# yours (e.g. the paper's CartPole table). Each command runs ROUNDS times (default 20) in turn
# with the others; prints the median and the slowest, in milliseconds. `dcs plot` is left out:
# it runs gnuplot, a program of its own.
# Usage: bench/cli/client_commands.sh   (BUILD_DIR: default build)
set -euo pipefail
dcs="$(realpath "${BUILD_DIR:-build}/services/dcs")"
rounds="${ROUNDS:-20}"
spec="$(mktemp --suffix=.yaml)"
cat > "$spec" <<'YAML'
name: tiny
seeds: 2
observe: [none, live]
env: cartpole
total_timesteps: 2048
pool: {size: 3}
evaluation: {freq: 1024, episodes: 2, contexts: {id: [0.5], ood_low: [0.1], ood_high: [1.0]}}
ppo: {n_steps: 512, batch_size: 64, n_epochs: 2}
conditions:
  - name: static
  - schedule: {family: sinusoidal, amplitude_frac: 0.25, period: 125}
YAML
if [ -n "${SWEEP_DATA_DIR:-}" ]; then
  data="$SWEEP_DATA_DIR"
  sweep="$SWEEP"
else
  data="$(mktemp -d)"
  "$dcs" up -d --data-dir "$data" > /dev/null
  trap '"$dcs" down --data-dir "$data" > /dev/null; rm -rf "$data"' EXIT
  sweep=$("$dcs" submit --data-dir "$data" "$spec" 2> /dev/null)
  "$dcs" watch --data-dir "$data" "$sweep" > /dev/null
fi
coordinator=$(sed -n 's/^coordinator: *//p' "$data/cluster.yaml")

python3 - "$rounds" "$dcs" "$data" "$coordinator" "$sweep" "$spec" <<'PY'
import statistics, subprocess, sys, time
rounds, dcs, data, coordinator, sweep, spec = int(sys.argv[1]), *sys.argv[2:]
at = ["--data-dir", data]
commands = {
    "dcs --help": [dcs, "--help"],
    "dcs version": [dcs, "version"],
    "dcs health": [dcs, "health", "--addr", coordinator],
    "dcs status": [dcs, "status", *at],
    "dcs runs": [dcs, "runs", *at],
    "dcs sweeps": [dcs, "sweeps", *at],
    "dcs submit --dry-run": [dcs, "submit", "--dry-run", spec, *at],
    "dcs watch (ended)": [dcs, "watch", sweep, *at],
    "dcs report": [dcs, "report", sweep, *at],
    "dcs report --checkpoint best --format latex": [
        dcs, "report", sweep, "--checkpoint", "best", "--format", "latex", *at],
    "dcs report --format json": [dcs, "report", sweep, "--format", "json", *at],
}
seconds = {name: [] for name in commands}
for _ in range(rounds):
    for name, command in commands.items():
        start = time.monotonic()
        done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        seconds[name].append(time.monotonic() - start)
        if done.returncode != 0:
            sys.exit(f"{name}: exit {done.returncode}: {done.stderr.decode()}")
width = max(map(len, commands))
print(f"{'command':{width}}  median ms  max ms  ({rounds} rounds, sweep {sweep})")
for name, values in seconds.items():
    print(f"{name:{width}}  {statistics.median(values) * 1e3:9.1f}  {max(values) * 1e3:6.1f}")
PY
rm -f "$spec"
