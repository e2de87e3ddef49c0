#!/usr/bin/env bash
# Load on loopback (issue 14, point 4): a coordinator, LEARNERS learners (each hosting up to
# RUNS / LEARNERS runs) and ACTORS actors, started here as separate processes with a fresh
# token, and a sweep of RUNS CartPole runs (CONFIG as the base, half static, half a sinusoid,
# STEPS_PER_RUN steps each: long enough that they still run when time is up) trained for
# SECONDS of wall time from its submission. Measures:
# - memory: every process's VmRSS each second into rss.csv (time_s, process, rss_kib), and its
#   VmHWM at the end; per kind (coordinator, learner, actor) RSS at start, peak and end, and the
#   least-squares slope over the second half (growing: it would add more than 5 % of its level
#   over a further half);
# - throughput: environment steps per second of all runs, from the coordinator's run progress
#   (`dcs runs`, every 10 s into progress.csv), over the window and over its last minute;
# - RPC latency: p50, p95 and p99 per method of grpc_server_handling_seconds scraped from every
#   coordinator and learner at the end (each kind's processes summed), interpolated within the
#   histogram's buckets as Prometheus's histogram_quantile does;
# - no deadlock: at the end every process answers its gRPC health check SERVING, every running
#   run advanced during the last minute, and every process stops within its grace on SIGTERM;
#   otherwise the script exits 1. Also counted: lapsed leases, refused rollouts, RPCs that did
#   not end OK, warnings and errors in the logs.
# Everything is kept in a temporary directory (printed; the coordinator's store removed at the
# end); RSS_PNG=file.png also draws RSS over time with gnuplot.
# Usage: bench/cluster/load.sh [ACTORS] [RUNS] [SECONDS]   (defaults 64 32 300)
#        bench/cluster/load.sh --report DIR   (the report again, from a directory it kept)
#   (BUILD_DIR: default build; LEARNERS: 2; CONFIG: configs/cartpole_length_pool7_static_blind.yaml;
#    STEPS_PER_RUN: 5000000; N_ENVS: 2, so that there is a slot per actor; RSS_PNG: none)
set -euo pipefail
bin="${BUILD_DIR:-build}/services"
actors="${1:-64}"
runs="${2:-32}"
seconds="${3:-300}"
learners="${LEARNERS:-2}"
config="${CONFIG:-configs/cartpole_length_pool7_static_blind.yaml}"
steps_per_run="${STEPS_PER_RUN:-5000000}"
n_envs="${N_ENVS:-2}"

# The report, from what a measurement kept in $dir (also: load.sh --report DIR).
report() {
  local failed=0
  python3 - "$dir" "$window" "$actors" "$runs" "$unhealthy" "$killed" "$stop_seconds" <<'PY' ||
import collections, csv, glob, math, os, re, sys
d, window = sys.argv[1], float(sys.argv[2])
actors, runs, unhealthy, killed, stop_s = map(int, sys.argv[3:])
kind = lambda name: re.sub(r"-\d+$", "", name)
failed = False

# Throughput and progress.
progress = collections.defaultdict(dict)  # time -> run -> (state, steps)
for row in csv.DictReader(open(f"{d}/progress.csv")):
    progress[float(row["time_s"])][row["run_id"]] = (row["state"], int(row["timesteps"]))
times = sorted(progress)
last = progress[times[-1]]
steps = sum(s for _, s in last.values())
minute_ago = max(t for t in times if t <= times[-1] - 55) if times[-1] >= 60 else times[0]
before = progress[minute_ago]
recent = steps - sum(s for _, s in before.values())
states = collections.Counter(state for state, _ in last.values())
stalled = [r for r, (state, s) in last.items()
           if state == "running" and r in before and s <= before[r][1]]
print(f"window {window:.0f} s: runs {dict(states)}; steps {steps:,} "
      f"({steps / window:,.0f} steps/s over the window, "
      f"{recent / (times[-1] - minute_ago):,.0f} steps/s over the last {times[-1] - minute_ago:.0f} s)")
per_run = sorted(s for _, s in last.values())
print(f"steps per run: min {per_run[0]:,}  median {per_run[len(per_run) // 2]:,}  max {per_run[-1]:,}")

# Memory.
series = collections.defaultdict(list)  # process -> [(t, kib)]
for row in csv.DictReader(open(f"{d}/rss.csv")):
    series[row["process"]].append((float(row["time_s"]), int(row["rss_kib"])))
hwm = dict(line.split() for line in open(f"{d}/hwm")) if os.path.exists(f"{d}/hwm") else {}
def slope(points):  # least squares, KiB per second
    n = len(points)
    mt, mk = sum(t for t, _ in points) / n, sum(k for _, k in points) / n
    var = sum((t - mt) ** 2 for t, _ in points)
    return sum((t - mt) * (k - mk) for t, k in points) / var if var else 0.0, mk
def growing(points):
    half = [p for p in points if p[0] >= points[-1][0] / 2]
    s, level = slope(half)
    span = half[-1][0] - half[0][0]
    return s, s * span > 0.05 * level
mib = lambda kib: kib / 1024
print("\nRSS (MiB)     processes  start  peak  end  VmHWM max | kind total: start  peak  end  "
      "slope over 2nd half (MiB/min)  growing")
kinds = collections.defaultdict(list)
for name in series: kinds[kind(name)].append(name)
grand = collections.defaultdict(int)
for k in ("coordinator", "learner", "actor"):
    names = kinds.get(k, [])
    if not names: continue
    start = [series[n][0][1] for n in names]
    peak = [max(v for _, v in series[n]) for n in names]
    end = [series[n][-1][1] for n in names]
    total = collections.defaultdict(int)  # second -> sum
    for n in names:
        for t, v in series[n]: total[t] += v  # one time per sampling pass
    for t, v in total.items(): grand[t] += v
    points = sorted(total.items())
    s, grows = growing(points)
    grown = [n for n in names if growing(series[n])[1]]
    fmt = lambda xs: (f"{mib(xs[0]):.0f}" if len(xs) == 1 else
                      f"{mib(min(xs)):.0f}-{mib(max(xs)):.0f}")
    print(f"{k:12s} {len(names):4d}  {fmt(start):>9s} {fmt(peak):>9s} {fmt(end):>9s} "
          f"{mib(max(int(hwm.get(n, 0)) for n in names)):6.0f} | "
          f"{mib(points[0][1]):7.0f} {mib(max(v for _, v in points)):6.0f} {mib(points[-1][1]):6.0f}  "
          f"{s * 60 / 1024:+8.2f}  {'YES' if grows else 'no'}"
          f"  (processes growing: {len(grown)}{': ' + ' '.join(grown[:8]) if grown else ''})")
points = sorted(grand.items())
print(f"all {sum(len(v) for v in kinds.values())} processes: start {mib(points[0][1]):.0f} MiB, "
      f"peak {mib(max(v for _, v in points)):.0f} MiB, end {mib(points[-1][1]):.0f} MiB")

# Latency per method, each kind's processes summed.
buckets = collections.defaultdict(lambda: collections.defaultdict(float))
types = {}
metric = collections.defaultdict(float)
codes = collections.defaultdict(float)
cpu = collections.defaultdict(float)
line_re = re.compile(r"^(\w+)(?:\{(.*)\})? (\S+)")
for path in sorted(glob.glob(f"{d}/metrics/*.txt")):
    k = kind(os.path.basename(path)[:-4])
    for line in open(path):
        m = line_re.match(line)
        if not m: continue
        name, labels, value = m[1], dict(re.findall(r'(\w+)="([^"]*)"', m[2] or "")), float(m[3])
        if name == "grpc_server_handling_seconds_bucket":
            key = (k, labels["grpc_service"].split(".")[-1], labels["grpc_method"])
            buckets[key][float(labels["le"])] += value
            types[key] = labels["grpc_type"]
        elif name == "grpc_server_handled_total" and labels.get("grpc_code") != "OK" and value:
            codes[(k, labels["grpc_method"], labels["grpc_code"])] += value
        elif name == "process_cpu_seconds_total":
            cpu[k] += value
        elif name in ("dcs_leases_expired_total", "dcs_rollouts_rejected_total",
                      "dcs_coordinator_rpc_failures_total", "dcs_rollouts_received_total",
                      "dcs_actor_slot_rebuilds_total", "dcs_actor_evaluation_jobs_total"):
            metric[name] += value
def quantile(q, b):
    bounds = sorted(b)
    total = b[bounds[-1]]
    rank, lower, below = q * total, 0.0, 0.0
    for bound in bounds:
        if b[bound] >= rank:
            if bound == math.inf: return lower  # above the largest finite bucket
            return lower + (bound - lower) * (rank - below) / (b[bound] - below)
        lower, below = bound, b[bound]
ms = lambda s: f"{s * 1e3:.2f}" if s < 0.1 else f"{s * 1e3:.0f}"
print("\nRPC latency (grpc_server_handling_seconds; ms; >= 10000 means above the last bucket)")
print(f"{'kind':12s} {'method':22s} {'type':14s} {'calls':>9s} {'p50':>8s} {'p95':>8s} {'p99':>8s}")
for key in sorted(buckets, key=lambda key: (key[0], -buckets[key][math.inf])):
    b = buckets[key]
    if not b[math.inf] or key[2] == "Check": continue  # health probes: this script's own
    print(f"{key[0]:12s} {key[2]:22s} {types[key]:14s} {b[math.inf]:9.0f} "
          f"{ms(quantile(0.5, b)):>8s} {ms(quantile(0.95, b)):>8s} {ms(quantile(0.99, b)):>8s}")
print("\nRPCs not OK: " + (", ".join(f"{k} {m} {c} x{v:.0f}" for (k, m, c), v in sorted(codes.items()))
                          or "none"))
print("counters: " + ", ".join(f"{n} {v:.0f}" for n, v in sorted(metric.items())))
print(f"CPU seconds: " + ", ".join(f"{k} {v:.0f}" for k, v in sorted(cpu.items())) +
      f" (over {window:.0f} s x {os.cpu_count()} cores)")

# Logs: warnings and errors per kind, the commonest messages.
logged = collections.Counter()
messages = collections.Counter()
for path in glob.glob(f"{d}/logs/*.log"):
    k = kind(os.path.basename(path)[:-4])
    for line in open(path, errors="replace"):
        m = re.match(r"\S+ (WARNING|ERROR|FATAL) ", line)
        if not m: continue
        logged[(k, m[1].lower())] += 1
        messages[(k, re.sub(r"\d+", "N", line.split(" ", 1)[-1].strip())[:150])] += 1
print("log lines: " + (", ".join(f"{k} {lvl} {n}" for (k, lvl), n in sorted(logged.items()))
                       or "no warnings or errors"))
for (k, message), n in messages.most_common(8):
    print(f"  {n:6d}  {k}: {message}")

print("\nno deadlock: "
      f"{len(series) - unhealthy}/{len(series)} processes SERVING at the end; "
      f"{len(stalled)} running runs without progress in the last minute"
      f"{' (' + ' '.join(stalled) + ')' if stalled else ''}; "
      f"{len(series) - killed}/{len(series)} stopped on SIGTERM within the grace ({stop_s} s)")
sys.exit(1 if stalled or unhealthy or killed or recent <= 0 else 0)
PY
    failed=1
  if [[ -n "${RSS_PNG:-}" ]]; then
  python3 - "$dir/rss.csv" "$dir/rss.dat" <<'PY'
import collections, csv, re, sys
by_time = collections.defaultdict(lambda: collections.defaultdict(list))
for row in csv.DictReader(open(sys.argv[1])):
    name = row["process"]
    kind = name if not name.startswith("actor") else "actor"
    by_time[round(float(row["time_s"]))][kind].append(int(row["rss_kib"]) / 1024)
kinds = sorted({k for v in by_time.values() for k in v}, key=lambda k: (k != "coordinator", k))
with open(sys.argv[2], "w") as out:
    out.write("time " + " ".join(k if k != "actor" else "actor_mean actor_max" for k in kinds) + "\n")
    for t in sorted(by_time):
        cols = []
        for k in kinds:
            v = by_time[t].get(k, [float("nan")])
            cols += [sum(v) / len(v), max(v)] if k == "actor" else [v[0]]
        out.write(f"{t} " + " ".join(f"{c:.1f}" for c in cols) + "\n")
PY
  gnuplot <<GP
set terminal pngcairo size 800,420 font ",10" noenhanced
set output "$RSS_PNG"
set title "RSS over time: $actors actors, $runs runs, $learners learners (the sweep submitted 2 s in)"
set xlabel "seconds since every process was SERVING"
set ylabel "RSS (MiB)"
set key outside right
set grid
plot for [i=2:*] "$dir/rss.dat" using 1:i with lines lw 2 title columnheader(i)
GP
  echo "RSS plot: $RSS_PNG"
fi
  return "$failed"
}

if [[ "${1:-}" == --report ]]; then  # the report again, from a kept directory
  dir="$2"
  read -r window actors runs learners unhealthy killed stop_seconds < "$dir/outcome"
  report
  exit
fi
dir="$(mktemp -d /tmp/dcs-load.XXXXXX)"
mkdir -p "$dir/logs" "$dir/run" "$dir/metrics"
dcs=("$bin/dcs" --token-file "$dir/token" --timeout 10s)

names=()  # every process started, in start order
pids=()
stop_processes() {  # actors, then learners, then the coordinator: SIGTERM, KILL after grace
  local grace="$1" killed=0 kind i deadline
  for kind in actor learner coordinator; do
    for i in "${!pids[@]}"; do
      [[ "${names[i]}" == "$kind"* ]] && { kill -TERM "${pids[i]}" 2> /dev/null || true; }
    done
    deadline=$((SECONDS + grace))
    for i in "${!pids[@]}"; do
      [[ "${names[i]}" == "$kind"* ]] || continue
      while kill -0 "${pids[i]}" 2> /dev/null && ((SECONDS < deadline)); do sleep 0.2; done
      if kill -0 "${pids[i]}" 2> /dev/null; then
        echo "${names[i]} (pid ${pids[i]}) did not stop within ${grace}s of SIGTERM: killed" >&2
        kill -KILL "${pids[i]}" 2> /dev/null || true
        killed=$((killed + 1))
      fi
      wait "${pids[i]}" 2> /dev/null || true
    done
  done
  pids=()
  return "$killed"
}
cleanup() {
  [[ -n "${sampler:-}" ]] && kill "$sampler" 2> /dev/null
  stop_processes 5 || true
  rm -rf "$dir/coordinator"
  echo "kept in $dir (rss.csv, progress.csv, logs/, metrics/)" >&2
}
trap cleanup EXIT
trap 'exit 130' INT TERM

start_process() {  # name program args...: starts it, waits for its port file
  local name="$1" program="$2"
  shift 2
  "$bin/$program" "$@" --listen 127.0.0.1:0 --metrics-listen 127.0.0.1:0 \
    --token-file "$dir/token" --port-file "$dir/run/$name.ports" > "$dir/logs/$name.log" 2>&1 &
  names+=("$name")
  pids+=($!)
}
port() { sed -n "s/^$2: *//p" "$dir/run/$1.ports"; }
wait_for_port_files() {
  local name deadline=$((SECONDS + 120))
  for name in "$@"; do
    until [[ -s "$dir/run/$name.ports" ]]; do
      ((SECONDS < deadline)) || { echo "$name did not start; see $dir/logs/$name.log" >&2; exit 1; }
      sleep 0.1
    done
  done
}

(umask 077 && od -An -tx1 -N32 /dev/urandom | tr -d ' \n' > "$dir/token")
start_process coordinator dcs-coordinator --data-dir "$dir/coordinator"
wait_for_port_files coordinator
coordinator="127.0.0.1:$(port coordinator grpc_port)"
max_runs=$(((runs + learners - 1) / learners))
for i in $(seq 1 "$learners"); do
  start_process "learner-$i" dcs-learner --coordinator "$coordinator" --max-runs "$max_runs"
done
for i in $(seq 1 "$actors"); do
  start_process "actor-$i" dcs-actor --coordinator "$coordinator"
done
wait_for_port_files "${names[@]}"
for name in "${names[@]}"; do  # a worker is SERVING once registered
  "${dcs[@]}" health --addr "127.0.0.1:$(port "$name" grpc_port)" --wait 120s > /dev/null ||
    { echo "$name was not SERVING; see $dir/logs/$name.log" >&2; exit 1; }
done
echo "started: coordinator $coordinator, $learners learners (--max-runs $max_runs), $actors actors"

# Every process's VmRSS each second.
for i in "${!names[@]}"; do echo "${names[i]} ${pids[i]}"; done > "$dir/processes"
python3 - "$dir/processes" "$dir/rss.csv" <<'PY' &
import sys, time
processes = [line.split() for line in open(sys.argv[1])]
start = time.monotonic()
with open(sys.argv[2], "w") as out:
    out.write("time_s,process,rss_kib\n")
    while True:
        now = time.monotonic() - start
        for name, pid in processes:
            try:
                with open(f"/proc/{pid}/status") as status:
                    for line in status:
                        if line.startswith("VmRSS:"):
                            out.write(f"{now:.1f},{name},{line.split()[1]}\n")
            except OSError:
                pass  # gone: noticed by the health check
        out.flush()
        time.sleep(max(0.0, 1.0 - (time.monotonic() - start - now)))
PY
sampler=$!
sleep 2

# The sweep: CONFIG without its seed, observe and schedule; two conditions in one mode.
{
  echo "name: load"
  echo "seeds: $((runs / 2))"
  echo "observe: [none]"
  sed -e '/^seed:/d' -e '/^observe:/d' -e '/^schedule:/d' \
      -e "s/^total_timesteps:.*/total_timesteps: $steps_per_run/" \
      -e "s/^n_envs:.*/n_envs: $n_envs/" "$config"
  echo "conditions:"
  echo "  - name: static"
  echo "  - schedule: {family: sinusoidal, amplitude_frac: 0.25, period: 125}"
} > "$dir/sweep.yaml"
((runs % 2 == 0)) || { echo "RUNS must be even (two conditions)" >&2; exit 2; }
submitted=$(date +%s.%N)
sweep=$("${dcs[@]}" --addr "$coordinator" submit "$dir/sweep.yaml")
echo "sweep $sweep: $runs runs of $steps_per_run steps ($config, n_envs $n_envs); ${seconds}s"

# Run progress every 10 s until SECONDS have passed since the submission.
echo "time_s,run_id,state,timesteps" > "$dir/progress.csv"
sample_progress() {
  local now
  now=$(python3 -c "import time; print(f'{time.time() - $submitted:.1f}')")
  "${dcs[@]}" --addr "$coordinator" runs -o json |
    python3 -c 'import json, sys
for r in json.load(sys.stdin).get("runs", []):
    print(",".join([sys.argv[1], r["run_id"], r["state"],
                    str(int(r.get("progress", {}).get("timesteps", 0)))]))' \
      "$now" >> "$dir/progress.csv"
}
end=$(python3 -c "print($submitted + $seconds)")
while python3 -c "import sys, time; sys.exit(0 if time.time() < $end - 10 else 1)"; do
  sample_progress || echo "dcs runs failed at $(date +%T)" >&2
  sleep 10
done
python3 -c "import time; time.sleep(max(0, $end - time.time()))"
sample_progress
window=$(python3 -c "import time; print(time.time() - $submitted)")

# The end: health of every process, the metrics of every process.
failed=0
unhealthy=0
for i in "${!names[@]}"; do
  if ! kill -0 "${pids[i]}" 2> /dev/null; then
    echo "DEADLOCK CHECK: ${names[i]} exited; see $dir/logs/${names[i]}.log" >&2
    unhealthy=$((unhealthy + 1))
  elif ! "${dcs[@]}" health --addr "127.0.0.1:$(port "${names[i]}" grpc_port)" \
         > /dev/null 2>&1; then
    echo "DEADLOCK CHECK: ${names[i]} did not answer SERVING to its health check" >&2
    unhealthy=$((unhealthy + 1))
  fi
  curl -s -m 10 "http://127.0.0.1:$(port "${names[i]}" metrics_port)/metrics" \
    > "$dir/metrics/${names[i]}.txt" || true
  awk '/^VmHWM:/ {print $2}' "/proc/${pids[i]}/status" 2> /dev/null |
    sed "s/^/${names[i]} /" >> "$dir/hwm" || true
done
((unhealthy == 0)) || failed=1
kill "$sampler" 2> /dev/null || true
wait "$sampler" 2> /dev/null || true
sampler=""
stopped_start=$SECONDS
if stop_processes 20; then killed=0; else killed=$?; fi
stop_seconds=$((SECONDS - stopped_start))
((killed == 0)) || failed=1

echo "$window $actors $runs $learners $unhealthy $killed $stop_seconds" > "$dir/outcome"
report || failed=1
echo "rss: $dir/rss.csv  progress: $dir/progress.csv"
exit "$failed"
