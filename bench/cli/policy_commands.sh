#!/usr/bin/env bash
# How long `dcs eval`, `dcs play` and `dcs export` take, start to exit, on a trained CartPole run
# of a local cluster (`dcs up`): the paper's static blind pool-7 config (150k steps), trained on
# the cluster first. `dcs eval` takes the run by its id (downloaded from the coordinator) over the
# issue's grid, pole length x gravity (40 x 16 cells, 30 episodes each), and writes its heatmap,
# once in its own process and once with --on-actors (the cluster's two actors run the cells);
# `dcs play` records one 500-step episode as MP4 with a strip; `dcs export` writes the state
# dict and layout. Each runs ROUNDS times (default 5) in turn with the others; prints the median
# and the slowest, in seconds, and the peak resident memory of the slowest.
# Usage: bench/cli/policy_commands.sh   (BUILD_DIR: default build)
set -euo pipefail
dcs="$(realpath "${BUILD_DIR:-build}/services/dcs")"
config="$(realpath configs/cartpole_length_pool7_static_blind.yaml)"
rounds="${ROUNDS:-5}"
data="$(mktemp -d)"
out="$(mktemp -d)"
"$dcs" up -d --data-dir "$data" > /dev/null
trap '"$dcs" down --data-dir "$data" > /dev/null; rm -rf "$data" "$out"' EXIT
"$dcs" train --cluster --data-dir "$data" --config "$config" --out "$out/run" > /dev/null 2>&1
run_id=$("$dcs" runs --data-dir "$data" -o json | python3 -c \
  'import json, sys; print(json.load(sys.stdin)["runs"][0]["run_id"])')

python3 - "$rounds" "$dcs" "$data" "$run_id" "$out" <<'PY'
import resource, statistics, subprocess, sys, time
rounds, dcs, data, run_id, out = int(sys.argv[1]), *sys.argv[2:]
commands = {
    "dcs eval RUN_ID --grid length=0.05:2:40 --grid gravity=2:25:16 --episodes 30 --out D":
        ["eval", run_id, "--grid", "length=0.05:2:40", "--grid", "gravity=2:25:16",
         "--episodes", "30", "--out", f"{out}/eval"],
    "dcs eval RUN_ID --on-actors (the same grid)":
        ["eval", run_id, "--on-actors", "--grid", "length=0.05:2:40", "--grid",
         "gravity=2:25:16", "--episodes", "30", "--out", f"{out}/eval-actors"],
    "dcs play RUN_DIR --context length=0.9 --out E.mp4 --strip S.png":
        ["play", f"{out}/run", "--context", "length=0.9", "--out", f"{out}/e.mp4",
         "--strip", f"{out}/s.png"],
    "dcs export RUN_DIR --out P.pt": ["export", f"{out}/run", "--out", f"{out}/p.pt"],
}
seconds = {name: [] for name in commands}
for _ in range(rounds):
    for name, args in commands.items():
        start = time.monotonic()
        subprocess.run([dcs, *args, "--data-dir", data], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        seconds[name].append(time.monotonic() - start)
for name, values in seconds.items():
    print(f"{name}: median {statistics.median(values):.2f} s, max {max(values):.2f} s")
print(f"peak RSS of a child: {resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024:.0f} MiB")
PY
