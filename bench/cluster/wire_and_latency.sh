#!/usr/bin/env bash
# One run of a config trained on a fresh local cluster (`dcs up`: a learner, an actor per core),
# then read from the processes' metrics: the bytes of rollouts on the wire per transition (the
# learner's dcs_rollout_bytes over the run's environment steps), and the latency from a policy
# version's publication to an actor's first step with it (dcs_policy_update_latency_seconds,
# summed over the actors), whose median and p99 are interpolated within the histogram's buckets
# as Prometheus's histogram_quantile does.
# Usage: bench/cluster/wire_and_latency.sh [CONFIG]   (BUILD_DIR: default build)
set -euo pipefail
dcs="${BUILD_DIR:-build}/services/dcs"
config="${1:-configs/cartpole_length_pool7_static_blind.yaml}"
data="$(mktemp -d)"
"$dcs" up -d --data-dir "$data" > /dev/null
trap '"$dcs" down --data-dir "$data" > /dev/null; rm -rf "$data"' EXIT
"$dcs" train --cluster --data-dir "$data" --config "$config" --out "$data/out" > /dev/null 2>&1

steps=$("$dcs" runs --data-dir "$data" -o json |
        python3 -c 'import json, sys; print(sum(int(r["progress"]["timesteps"])
                    for r in json.load(sys.stdin)["runs"]))')
for process in $(sed -n 's/^ *- name: *//p' "$data/cluster.yaml"); do
  metrics=$(sed -n "/name: $process\$/,/metrics:/s/^ *metrics: *//p" "$data/cluster.yaml")
  curl -s "http://$metrics/metrics"
done | python3 -c '
import collections, re, sys
steps = int(sys.argv[1])
rollout_bytes = rollouts = 0.0
buckets = collections.defaultdict(float)  # upper bound -> cumulative count, over the actors
for line in sys.stdin:
    if line.startswith("dcs_rollout_bytes_sum "): rollout_bytes += float(line.split()[1])
    if line.startswith("dcs_rollout_bytes_count "): rollouts += float(line.split()[1])
    bucket = re.match(r"dcs_policy_update_latency_seconds_bucket\{le=\"([^\"]+)\"\} (\S+)", line)
    if bucket: buckets[float(bucket[1])] += float(bucket[2])
bounds = sorted(buckets)
total = buckets[bounds[-1]]
def quantile(q):
    rank, lower, below = q * total, 0.0, 0.0
    for bound in bounds:
        if buckets[bound] >= rank:
            if bound == float("inf"): return lower
            return lower + (bound - lower) * (rank - below) / (buckets[bound] - below)
        lower, below = bound, buckets[bound]
within = ", ".join(f"{buckets[b]:.0f} within {b * 1e3:g} ms" for b in bounds[:4])
print(f"steps {steps}  rollouts {rollouts:.0f}  rollout_bytes {rollout_bytes:.0f}  "
      f"bytes_per_transition {rollout_bytes / steps:.2f}")
print(f"update_to_first_step: updates {total:.0f}  median_ms {quantile(0.5) * 1e3:.2f}  "
      f"p99_ms {quantile(0.99) * 1e3:.1f}  ({within})")
' "$steps"
