#!/usr/bin/env bash
# Starts docker-compose.yml's cluster for real and runs a small sweep through it: the image built
# from ./Dockerfile, the coordinator, a learner and two actors, Prometheus scraping all four,
# Alertmanager; the sweep is submitted and watched to its end with the image's own `dcs`, then
# Prometheus must see every process up and the learner's steps. Then the coordinator is
# stopped: Alertmanager must receive DcsCoordinatorDown firing, and DcsWorkersCutOff (which
# fires a minute later, as the workers lose it) held back by it. Grafana is left out (not
# packaged in Debian, and no registry may be reachable). An image that cannot be found locally
# or pulled is made from Debian's packages: the Dockerfile's Debian 12 bases by
# scripts/debian-base-image, Prometheus and Alertmanager as stand-in images of Debian's
# prometheus and prometheus-alertmanager packages (same flags).
#
#   tests/deploy/check_compose_cluster.sh REPO_ROOT [--tls]
#
# With --tls, the cluster runs with docker-compose.tls.yml on certificates of scripts/make-certs:
# every call between containers is mutual TLS checked against the cluster's one server name,
# and a call without a certificate is refused.
#
# Runs only with DCS_CONTAINER_TESTS=1, a container engine that answers (`docker info`) and
# docker-compose; else exits 77 (skipped). It builds the image: the first time as long as the
# programs' part of `make build`, then seconds while the sources are unchanged.
# Uses its own compose project (dcs-check-<pid>) and removes it, volumes included, on exit; the
# published ports (127.0.0.1:50051, :9090 and :9093) must be free.
set -euo pipefail

root=${1:?usage: check_compose_cluster.sh REPO_ROOT [--tls]}
mode=${2:-}
case "$mode" in
  ""|--tls) ;;
  *) echo "usage: check_compose_cluster.sh REPO_ROOT [--tls]" >&2; exit 2 ;;
esac
cd "$root"

step() { echo "check_compose_cluster: $*"; }
fail() {
  echo "check_compose_cluster: FAIL: $*" >&2
  exit 1
}
skip() {
  echo "check_compose_cluster: SKIP: $*"
  exit 77
}

[ "${DCS_CONTAINER_TESTS:-0}" = 1 ] \
  || skip "set DCS_CONTAINER_TESTS=1 to run it (it builds the image: minutes, more the first time)"
command -v docker >/dev/null 2>&1 || skip "no docker client"
command -v docker-compose >/dev/null 2>&1 || skip "no docker-compose"
docker info >/dev/null 2>&1 || skip "no container engine answers (docker info fails)"
for port in 50051 9090 9093; do
  if (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then
    fail "127.0.0.1:$port is in use; the compose cluster publishes it"
  fi
done

# The cluster's token: every service requires it, and `dcs` in the coordinator's container has it.
DCS_TOKEN=$(openssl rand -hex 32)
export DCS_TOKEN
work=$(mktemp -d)
project="dcs-check-$$"
compose=(docker-compose -p "$project" -f docker-compose.yml -f "$work/override.yml")
if [ "$mode" = --tls ]; then
  compose+=(-f docker-compose.tls.yml)
  export DCS_TLS_DIR="$work/certificates"
fi
cleanup() {
  local status=$?
  if [ "$status" -ne 0 ] && [ -f "$work/override.yml" ]; then
    "${compose[@]}" ps >&2 || true
    "${compose[@]}" logs --no-color --tail=20 >&2 || true
  fi
  "${compose[@]}" down -v --remove-orphans >/dev/null 2>&1 || true
  rm -rf "$work"
}
trap cleanup EXIT

# The Dockerfile's base images: here, pulled, or made from Debian's packages.
for base in $(sed -nE 's/^FROM ([^ ]+).*/\1/p' Dockerfile); do
  if ! docker image inspect "$base" >/dev/null 2>&1 && ! docker pull -q "$base" >/dev/null 2>&1
  then
    step "$base is neither here nor in a registry: made from Debian's packages"
    scripts/debian-base-image || fail "scripts/debian-base-image could not make $base"
  fi
done

# Prometheus and Alertmanager: the pinned image if it is here or can be pulled, else a stand-in
# of Debian's package, its program as the entry point (compose passes the same flags), run as
# nobody with its data directory (the one compose mounts a volume at) nobody's.
image_or_debian() {
  local service=$1 package=$2 program=$3 data=$4 image
  image=$(docker-compose -f docker-compose.yml config \
            | awk -v s="  $service:" '$0 == s {p=1} p && /image:/ {print $2; exit}')
  if docker image inspect "$image" >/dev/null 2>&1 || docker pull -q "$image" >/dev/null 2>&1
  then
    step "$service from $image" >&2
    echo "$image"
    return
  fi
  image=dcs-check/$service-debian:latest
  step "$service from a stand-in of Debian's $package package ($image)" >&2
  mkdir -p "$work/$service"
  cat >"$work/$service/Dockerfile" <<EOF
FROM debian:bookworm-slim
RUN apt-get update \\
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $package \\
 && rm -rf /var/lib/apt/lists/* \\
 && install -d -o nobody -g nogroup $data
USER nobody
ENTRYPOINT ["$program"]
EOF
  docker build -q -t "$image" "$work/$service" >/dev/null \
    || fail "could not build the $service stand-in image"
  echo "$image"
}
prometheus_image=$(image_or_debian prometheus prometheus /usr/bin/prometheus /prometheus)
alertmanager_image=$(image_or_debian alertmanager prometheus-alertmanager \
                       /usr/bin/prometheus-alertmanager /alertmanager)
cat >"$work/override.yml" <<EOF
services:
  prometheus:
    image: $prometheus_image
  alertmanager:
    image: $alertmanager_image
EOF

step "building the DCS image (docker-compose build coordinator)"
"${compose[@]}" build -q coordinator >/dev/null || fail "docker-compose build coordinator failed"

if [ "$mode" = --tls ]; then
  scripts/make-certs "$DCS_TLS_DIR" >/dev/null || fail "scripts/make-certs failed"
  step "certificates for the one server name in $DCS_TLS_DIR"
fi

step "up: coordinator, learner, 2 actors, prometheus, alertmanager (not grafana)${mode:+, over" \
  "mutual TLS}"
"${compose[@]}" up -d --scale actor=2 coordinator learner actor prometheus alertmanager \
  || fail "docker-compose up failed"

# Every DCS container healthy (a worker is healthy once registered with the coordinator).
deadline=$((SECONDS + 120))
while :; do
  states=$(for id in $("${compose[@]}" ps -q coordinator learner actor); do
             docker inspect -f '{{.Name}} {{.State.Health.Status}}' "$id"
           done)
  if [ "$(grep -c ' healthy$' <<<"$states")" -eq 4 ]; then break; fi
  [ "$SECONDS" -lt "$deadline" ] || fail "not every DCS container became healthy: $states"
  sleep 2
done
step "healthy: $(tr '\n' ' ' <<<"$states")"

dcs() { "${compose[@]}" exec -T coordinator dcs --addr 127.0.0.1:50051 "$@"; }
if [ "$mode" = --tls ]; then
  # The same `dcs status` in plaintext, without the container's certificate: the coordinator's
  # TLS handshake refuses it (UNAVAILABLE, not the client's own refusal of its flags).
  if out=$("${compose[@]}" exec -T coordinator \
             env -u DCS_TLS_CERT -u DCS_TLS_KEY -u DCS_TLS_CA -u DCS_TLS_SERVER_NAME \
             dcs --addr 127.0.0.1:50051 --timeout 5s status 2>&1); then
    fail "the coordinator answered a call without TLS: $out"
  fi
  [[ "$out" == *UNAVAILABLE* ]] || fail "a call without TLS failed, but not at the server: $out"
  step "refused without TLS: $(tail -1 <<<"$out")"
fi
status=$(dcs status)
echo "$status"
if [ "$(grep -cE '^learner .* alive ' <<<"$status")" -ne 1 ] \
   || [ "$(grep -cE '^actor .* alive ' <<<"$status")" -ne 2 ]; then
  fail "dcs status does not list 1 learner and 2 actors alive"
fi

# A small sweep: two conditions, two seeds, runs of 1536 steps (tests/integration/sweep_test.cc).
"${compose[@]}" exec -T coordinator sh -c 'cat > /tmp/small.yaml' <<'EOF'
name: small
seeds: 2
observe: [none]
env: cartpole
total_timesteps: 1536
feature: length
training_range: [0.35, 0.75]
pool: {size: 3}
evaluation: {freq: 512, episodes: 2, contexts: {id: [0.5], ood_low: [0.1], ood_high: [1.0]}}
ppo: {n_steps: 256, batch_size: 64, n_epochs: 2}
conditions:
  - name: static
  - schedule: {family: sinusoidal, amplitude_frac: 0.5, period: 40}
EOF
sweep=$(dcs submit /tmp/small.yaml) || fail "dcs submit failed: $sweep"
step "submitted $sweep; watching it"
timeout 600 "${compose[@]}" exec -T coordinator dcs --addr 127.0.0.1:50051 watch "$sweep" \
  || fail "dcs watch $sweep did not end with the sweep completed"
dcs report "$sweep" || fail "dcs report $sweep failed"

# Prometheus scrapes all four processes (the actors found through Docker's DNS).
query() {
  python3 -c 'import sys, urllib.parse, urllib.request
url = "http://127.0.0.1:9090/api/v1/query?" + urllib.parse.urlencode({"query": sys.argv[1]})
print(urllib.request.urlopen(url, timeout=5).read().decode())' "$1"
}
deadline=$((SECONDS + 60))
while :; do
  up=$(query 'sum by (job) (up)' || true)
  if grep -q '"job":"coordinator"},"value":\[[0-9.]*,"1"\]' <<<"$up" \
     && grep -q '"job":"learner"},"value":\[[0-9.]*,"1"\]' <<<"$up" \
     && grep -q '"job":"actor"},"value":\[[0-9.]*,"2"\]' <<<"$up"; then
    break
  fi
  [ "$SECONDS" -lt "$deadline" ] || fail "Prometheus does not see every process up: $up"
  sleep 2
done
step "Prometheus: up by job: $up"
# The runs' own series end with them (a 4-run sweep of 1536 steps lasts a few seconds); what
# stays: the actors' step counters (4 runs x 1536 steps) and the coordinator's runs by state,
# through the recording rule of deploy/prometheus/rules.yml.
deadline=$((SECONDS + 30))
while :; do
  steps=$(query 'sum(dcs_actor_env_steps_total) >= 6144' || true)
  completed=$(query 'state:dcs_runs:sum{state="completed"} == 4' || true)
  if grep -q '"result":\[{' <<<"$steps" && grep -q '"result":\[{' <<<"$completed"; then break; fi
  [ "$SECONDS" -lt "$deadline" ] \
    || fail "Prometheus lacks the sweep's steps or runs: $steps $completed"
  sleep 2
done
step "Prometheus: sum(dcs_actor_env_steps_total) >= 6144: $steps"
step "Prometheus: state:dcs_runs:sum{state=\"completed\"} == 4: $completed"

# Alerts, from the real rules to Alertmanager: the coordinator stopped, DcsCoordinatorDown
# fires after its minute; the workers, cut off from it, fire DcsWorkersCutOff after two, which
# Alertmanager holds back, naming DcsCoordinatorDown. The receiver is the config's placeholder,
# so Alertmanager's own view is what is checked (delivery: tests/integration/alertmanager_test.cc).
step "stopping the coordinator: Alertmanager must get DcsCoordinatorDown firing, and" \
  "DcsWorkersCutOff held back by it"
"${compose[@]}" stop coordinator >/dev/null || fail "docker-compose stop coordinator failed"
alerts() {
  python3 -c 'import json, urllib.request
alerts = json.load(urllib.request.urlopen("http://127.0.0.1:9093/api/v2/alerts", timeout=5))
names = {a["fingerprint"]: a["labels"]["alertname"] for a in alerts}
for a in alerts:
    by = ",".join(names.get(f, f) for f in a["status"]["inhibitedBy"])
    print(a["labels"]["alertname"], a["status"]["state"], by or "-")'
}
deadline=$((SECONDS + 300))
while :; do
  held=$(alerts || true)
  if grep -qx 'DcsCoordinatorDown active -' <<<"$held" \
     && grep -qx 'DcsWorkersCutOff suppressed DcsCoordinatorDown' <<<"$held"; then
    break
  fi
  [ "$SECONDS" -lt "$deadline" ] \
    || fail "Alertmanager lacks DcsCoordinatorDown firing and DcsWorkersCutOff held back by it:" \
            "$(tr '\n' ';' <<<"$held")"
  sleep 5
done
step "Alertmanager: $(tr '\n' ';' <<<"$held")"

step "the composed cluster ran a sweep and raised its alerts"
