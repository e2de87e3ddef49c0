#!/usr/bin/env bash
# Checks the container files without a container engine (shared/spec/operations.md §3.5):
# docker-compose.yml as docker-compose parses it, Prometheus's compose scrape config
# with promtool, the compose file against the conventions of §3.2-3.4 and the scrape config,
# and the Dockerfile against §3.1 (by grep: hadolint is not packaged). Quick: no image is built.
#
#   tests/deploy/check_compose.sh REPO_ROOT
#
# Prints each check; exits 1 at the first file that breaks one, naming the file and the problem.
set -euo pipefail

root=${1:?usage: check_compose.sh REPO_ROOT}
cd "$root"

fail() {
  echo "check_compose: FAIL: $*" >&2
  exit 1
}
step() {
  echo "check_compose: $*"
}
need() {
  command -v "$1" >/dev/null 2>&1 || fail "$1 is not installed (Debian package $2; scripts/bootstrap installs it)"
}

need docker-compose docker-compose
need promtool prometheus
need python3 python3
python3 -c 'import yaml' 2>/dev/null || fail "python3's yaml module is missing (Debian package python3-yaml)"

for file in Dockerfile .dockerignore docker-compose.yml .env deploy/prometheus/compose.yml; do
  [ -f "$file" ] || fail "$file is missing"
done

# --- docker-compose.yml as Compose reads it -------------------------------------------------
# The cluster's token comes from the environment, and without it Compose must refuse to start.
step "docker-compose.yml requires DCS_TOKEN"
if out=$(env -u DCS_TOKEN docker-compose -f docker-compose.yml config -q 2>&1) ||
    [[ "$out" != *DCS_TOKEN* ]]; then
  fail "docker-compose.yml starts a cluster without DCS_TOKEN (the services would take calls" \
    "from anyone): ${out:-no error}"
fi
export DCS_TOKEN=check-compose-token-0123456789abcdef0123456789abcdef
step "docker-compose $(docker-compose version --short) config -q docker-compose.yml"
if ! out=$(docker-compose -f docker-compose.yml config -q 2>&1); then
  fail "docker-compose refuses docker-compose.yml: $out"
fi
# `docker compose` (v2) is not packaged in Debian 12; check with it too where it exists.
if docker compose version >/dev/null 2>&1; then
  step "docker compose $(docker compose version --short) config -q docker-compose.yml"
  if ! out=$(docker compose -f docker-compose.yml config -q 2>&1); then
    fail "docker compose (v2) refuses docker-compose.yml: $out"
  fi
else
  step "docker compose (v2) is not installed: checked with docker-compose 1.29 only"
fi

# --- Prometheus's scrape config for compose ---------------------------------------------------
step "promtool check config deploy/prometheus/compose.yml (and the rule files it names)"
if ! out=$(promtool check config deploy/prometheus/compose.yml 2>&1); then
  fail "promtool check config deploy/prometheus/compose.yml: $out"
fi

# --- docker-compose.yml against the conventions and the scrape config ----------------------
# Read as docker-compose resolves it (anchors merged, .env applied), plus the file as written
# for the keys docker-compose drops or adds.
step "docker-compose.yml: services, probes, start-up order, ports, volumes, metrics targets"
resolved=$(docker-compose -f docker-compose.yml config)
RESOLVED="$resolved" python3 - <<'EOF' || exit 1
import os
import re
import sys

import yaml

def fail(message):
    print(f"check_compose: FAIL: {message}", file=sys.stderr)
    sys.exit(1)

with open("docker-compose.yml") as f:
    written = yaml.safe_load(f)
for key in ("name", "version"):
    if key in written:
        fail(f"docker-compose.yml: top-level '{key}:' key (Debian's docker-compose 1.29 refuses "
             "'name', and 'version' is obsolete; the project's name is in .env)")
with open(".env") as f:
    if not re.search(r"^COMPOSE_PROJECT_NAME=\S+", f.read(), re.M):
        fail(".env: no COMPOSE_PROJECT_NAME=")

compose = yaml.safe_load(os.environ["RESOLVED"])
services = compose.get("services", {})
for name in ("coordinator", "learner", "actor", "prometheus", "grafana"):
    if name not in services:
        fail(f"docker-compose.yml: no '{name}' service")

networks = compose.get("networks") or {}
if len(networks) != 1:
    fail(f"docker-compose.yml: want one user-defined network, found {sorted(networks)}")
network = next(iter(networks))
if (networks[network] or {}).get("driver", "bridge") != "bridge":
    fail(f"docker-compose.yml: network '{network}' is not a bridge")

def flag(command, name):
    """The value of --name=value or --name value in a command list, else None."""
    for i, arg in enumerate(command):
        if arg.startswith(f"--{name}="):
            return arg.split("=", 1)[1]
        if arg == f"--{name}" and i + 1 < len(command):
            return command[i + 1]
    return None

def port_of(address, what):
    match = re.fullmatch(r"(.*):(\d+)", address or "")
    if not match:
        fail(what)
    return match.group(1), int(match.group(2))

# Every service joins the one network; only user-facing ports are published, on loopback.
published = {"coordinator", "prometheus", "grafana"}
for name, service in services.items():
    if network not in (service.get("networks") or {}):
        fail(f"docker-compose.yml: service '{name}' is not on network '{network}'")
    ports = service.get("ports") or []
    if ports and name not in published:
        fail(f"docker-compose.yml: service '{name}' publishes ports {ports}; only "
             f"{sorted(published)} may")
    for port in ports:
        host_ip = port.get("host_ip") if isinstance(port, dict) else str(port).split(":")[0]
        if host_ip != "127.0.0.1":
            fail(f"docker-compose.yml: service '{name}' publishes {port} beyond 127.0.0.1")
    image = service.get("image", "")
    if name in ("prometheus", "grafana") and (":" not in image or image.endswith(":latest")):
        fail(f"docker-compose.yml: service '{name}' image '{image}' has no pinned tag")

# The DCS servers: the services that run a dcs-* program.
dcs = {name: s for name, s in services.items()
       if (s.get("command") or [""])[0].startswith("dcs-")}
if set(dcs) != {"coordinator", "learner", "actor"}:
    fail(f"docker-compose.yml: DCS services are {sorted(dcs)}, want coordinator, learner, actor")

metrics_ports = {}
for name, service in dcs.items():
    command = service["command"]
    host, grpc_port = port_of(flag(command, "listen"),
                              f"docker-compose.yml: service '{name}': no --listen host:port")
    if host != "0.0.0.0":
        fail(f"docker-compose.yml: service '{name}' listens on {host}, not 0.0.0.0")
    host, metrics_ports[name] = port_of(
        flag(command, "metrics-listen"),
        f"docker-compose.yml: service '{name}': no --metrics-listen host:port")
    if host != "0.0.0.0":
        fail(f"docker-compose.yml: service '{name}' serves metrics on {host}, not 0.0.0.0")
    check = service.get("healthcheck") or {}
    test = check.get("test") or []
    if isinstance(test, str) or test[:2] != ["CMD", "dcs"] or "health" not in test:
        fail(f"docker-compose.yml: service '{name}' healthcheck {test!r} is not "
             "[\"CMD\", \"dcs\", ..., \"health\", ...]")
    addr = flag(test, "addr")
    if addr != f"127.0.0.1:{grpc_port}":
        fail(f"docker-compose.yml: service '{name}' healthcheck asks {addr}, but the service "
             f"listens on port {grpc_port}")
    for key in ("interval", "timeout", "retries", "start_period"):
        if key not in check:
            fail(f"docker-compose.yml: service '{name}' healthcheck has no explicit '{key}'")
    if (service.get("environment") or {}).get("DCS_TOKEN") != os.environ["DCS_TOKEN"]:
        fail(f"docker-compose.yml: service '{name}' does not take DCS_TOKEN from the "
             "environment: it would not hold the cluster's token")
    if "stop_grace_period" not in service:
        fail(f"docker-compose.yml: service '{name}' has no stop_grace_period")
    if name != "coordinator":
        if service.get("restart") != "unless-stopped":
            fail(f"docker-compose.yml: worker '{name}' restart is {service.get('restart')!r}, "
                 "want unless-stopped")
        coordinator_flag = flag(command, "coordinator")
        if coordinator_flag != "coordinator:50051":
            fail(f"docker-compose.yml: worker '{name}' dials --coordinator={coordinator_flag}")
        condition = ((service.get("depends_on") or {}).get("coordinator") or {}).get("condition")
        if condition != "service_healthy":
            fail(f"docker-compose.yml: worker '{name}' does not wait for the coordinator with "
                 f"condition service_healthy (has {condition!r})")

actor = services["actor"]
for key in ("container_name", "ports", "hostname"):
    if actor.get(key):
        fail(f"docker-compose.yml: the actor service is scaled (--scale actor=N) but sets '{key}'")

# Mounts as (type, source, target, read_only): docker-compose 1.29 prints them short
# ("src:target:mode"), v2 long (dicts).
named_volumes = compose.get("volumes") or {}

def mounts(service):
    result = []
    for v in services[service].get("volumes") or []:
        if isinstance(v, dict):
            result.append((v.get("type"), v.get("source"), v.get("target"),
                           bool(v.get("read_only"))))
            continue
        parts = str(v).split(":")
        source, target = parts[0], parts[1] if len(parts) > 1 else parts[0]
        mode = parts[2] if len(parts) > 2 else "rw"
        kind = "volume" if source in named_volumes else "bind"
        result.append((kind, source, target, "ro" in mode.split(",")))
    return result

# The coordinator's store is a named volume at its --data-dir.
data_dir = flag(services["coordinator"]["command"], "data-dir")
if not any(kind == "volume" and source in named_volumes and target == data_dir
           for kind, source, target, _ in mounts("coordinator")):
    fail(f"docker-compose.yml: the coordinator's --data-dir {data_dir} is not a named volume")

def bind_ro(service, source_suffix, target):
    found = [m for m in mounts(service) if m[0] == "bind" and m[2] == target]
    if not found or not found[0][1].rstrip("/").endswith(source_suffix):
        fail(f"docker-compose.yml: {service} does not mount ./{source_suffix} at {target}")
    if not found[0][3]:
        fail(f"docker-compose.yml: {service} mounts ./{source_suffix} writable, want :ro")

# Prometheus reads deploy/prometheus/compose.yml from the read-only mount of deploy/prometheus.
bind_ro("prometheus", "deploy/prometheus", "/etc/prometheus")
config_file = flag(services["prometheus"].get("command") or [], "config.file")
if config_file != "/etc/prometheus/compose.yml":
    fail(f"docker-compose.yml: prometheus --config.file={config_file}, want "
         "/etc/prometheus/compose.yml")

# Grafana: provisioning and dashboards read-only, anonymous viewers.
bind_ro("grafana", "deploy/grafana/provisioning", "/etc/grafana/provisioning")
bind_ro("grafana", "deploy/grafana/dashboards", "/var/lib/grafana/dashboards")
environment = services["grafana"].get("environment") or {}
if str(environment.get("GF_AUTH_ANONYMOUS_ENABLED")).lower() != "true":
    fail("docker-compose.yml: grafana: GF_AUTH_ANONYMOUS_ENABLED is not true")
if environment.get("GF_AUTH_ANONYMOUS_ORG_ROLE") != "Viewer":
    fail("docker-compose.yml: grafana: GF_AUTH_ANONYMOUS_ORG_ROLE is not Viewer")

# Every DCS service's metrics port is a target of the scrape config: static targets by service
# name, or a DNS name (every replica) with that port.
with open("deploy/prometheus/compose.yml") as f:
    prometheus = yaml.safe_load(f)
targets = set()
for job in prometheus.get("scrape_configs") or []:
    for static in job.get("static_configs") or []:
        for target in static.get("targets") or []:
            targets.add(target)
    for dns in job.get("dns_sd_configs") or []:
        for dns_name in dns.get("names") or []:
            targets.add(f"{dns_name}:{dns.get('port')}")
for name, port in sorted(metrics_ports.items()):
    if f"{name}:{port}" not in targets:
        fail(f"deploy/prometheus/compose.yml scrapes no '{name}:{port}' (docker-compose.yml: "
             f"{name} serves metrics on {port}); its targets: {sorted(targets)}")
jobs = {job.get("job_name"): job for job in prometheus.get("scrape_configs") or []}
if not (jobs.get("actor") or {}).get("dns_sd_configs"):
    fail("deploy/prometheus/compose.yml: job 'actor' does not find the replicas by dns_sd_configs")
EOF

# --- Dockerfile against §3.1 (grep: hadolint is not packaged) ------------------------------
step "Dockerfile: two stages, apt hygiene, non-root user, EXPOSE, HEALTHCHECK, tini, exec form"
# Instructions one per line: continuation lines joined, comments dropped.
instructions=$(sed -e '/^[[:space:]]*#/d' Dockerfile | sed -e ':a' -e '/\\$/{N;s/\\\n/ /;ba}')
froms=$(grep -cE '^FROM ' <<<"$instructions" || true)
[ "$froms" -eq 2 ] || fail "Dockerfile: $froms FROM lines, want 2 (a build stage and a runtime stage)"
grep -qE '^FROM debian:bookworm AS [a-z]+' <<<"$instructions" \
  || fail "Dockerfile: the first stage is not 'FROM debian:bookworm AS <name>'"
[ "$(grep -E '^FROM ' <<<"$instructions" | tail -1)" = "FROM debian:bookworm-slim" ] \
  || fail "Dockerfile: the last stage is not 'FROM debian:bookworm-slim'"
grep -qE '^COPY --from=' <<<"$instructions" \
  || fail "Dockerfile: the runtime stage copies nothing from the build stage (COPY --from=)"
while IFS= read -r run; do
  for part in 'apt-get update' '--no-install-recommends' 'rm -rf /var/lib/apt/lists/\*'; do
    grep -qE -- "$part" <<<"$run" \
      || fail "Dockerfile: a RUN with apt-get install lacks '${part//\\/}' in the same RUN: $run"
  done
done < <(grep -E '^RUN .*apt-get install' <<<"$instructions")
! grep -qE '^RUN .*apt-get (dist-)?upgrade' <<<"$instructions" \
  || fail "Dockerfile: runs apt-get upgrade (take the base image's packages as they are)"
runtime=$(awk '/^FROM /{n++} n==2' <<<"$instructions")
user=$( (grep -E '^USER ' <<<"$runtime" || true) | tail -1 | awk '{print $2}')
[ -n "$user" ] || fail "Dockerfile: the runtime stage has no USER (it would run as root)"
case "${user%%:*}" in
  root|0) fail "Dockerfile: the runtime stage runs as $user" ;;
esac
grep -qE '^ENTRYPOINT \[ *"/usr/bin/tini", *"--" *\]' <<<"$runtime" \
  || fail 'Dockerfile: no exec-form ENTRYPOINT ["/usr/bin/tini", "--"] in the runtime stage'
grep -qE '^CMD \[' <<<"$runtime" || fail "Dockerfile: the runtime stage's CMD is not in exec form"
grep -qE '^HEALTHCHECK .*CMD \[ *"dcs",.*"health"' <<<"$runtime" \
  || fail 'Dockerfile: no HEALTHCHECK ... CMD ["dcs", ..., "health", ...] in the runtime stage'
grep -qE '^RUN .*apt-get install.* tini( |$)' <<<"$runtime" \
  || fail "Dockerfile: the runtime stage does not install tini"
exposed=$( (grep -E '^EXPOSE ' <<<"$runtime" || true) | cut -d' ' -f2- | tr ' ' '\n')
for port in $(docker-compose -f docker-compose.yml config \
                | grep -oE -- '--(metrics-)?listen=0\.0\.0\.0:[0-9]+' | sed 's/.*://' | sort -u); do
  grep -qx "$port" <<<"$exposed" || fail "Dockerfile: port $port (docker-compose.yml) is not EXPOSEd"
done
for pattern in .git build; do
  grep -qx "$pattern" .dockerignore || fail ".dockerignore: does not exclude $pattern"
done

step "all checks passed"
