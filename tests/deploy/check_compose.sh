#!/usr/bin/env bash
# Checks the container files without a container engine:
# docker-compose.yml as docker-compose parses it, Prometheus's compose scrape config
# with promtool, the compose file against DCS's conventions (a token required, health checks,
# loopback ports, named volumes) and the scrape config and its Alertmanager,
# docker-compose.tls.yml merged with it (mutual TLS for every DCS service), and the Dockerfile
# against its own (two stages, non-root, tini, exec-form CMD; by grep: hadolint is not
# packaged). Quick: no image is built.
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

for file in Dockerfile .dockerignore docker-compose.yml docker-compose.tls.yml .env \
    deploy/prometheus/compose.yml deploy/alertmanager/alertmanager.yml; do
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
step "docker-compose.yml: services, probes, start-up order, ports, volumes, metrics targets," \
  "Alertmanager, pinned kernels"
resolved=$(docker-compose -f docker-compose.yml config)
RESOLVED="$resolved" python3 - <<'EOF' || exit 1
import os
import re
import sys

import yaml

sys.path.insert(0, "tests/deploy")
import compose_mounts  # noqa: E402
from command_flags import flag  # noqa: E402
from pinned_kernels import torch_programs, unpinned  # noqa: E402

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
for name in ("coordinator", "learner", "actor", "prometheus", "alertmanager", "grafana"):
    if name not in services:
        fail(f"docker-compose.yml: no '{name}' service")

networks = compose.get("networks") or {}
if len(networks) != 1:
    fail(f"docker-compose.yml: want one user-defined network, found {sorted(networks)}")
network = next(iter(networks))
if (networks[network] or {}).get("driver", "bridge") != "bridge":
    fail(f"docker-compose.yml: network '{network}' is not a bridge")

def port_of(address, what):
    match = re.fullmatch(r"(.*):(\d+)", address or "")
    if not match:
        fail(what)
    return match.group(1), int(match.group(2))

# Every service joins the one network; only user-facing ports are published, on loopback.
published = {"coordinator", "prometheus", "alertmanager", "grafana"}
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
    if name in ("prometheus", "alertmanager", "grafana") and \
            (":" not in image or image.endswith(":latest")):
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
    # A program that links libtorch starts with the pinned numeric kernels, or it starts
    # libtorch, finds them unset and runs itself again with them.
    if command[0] in torch_programs():
        wrong = unpinned(service.get("environment") or {})
        if wrong:
            fail(f"docker-compose.yml: service '{name}' runs {command[0]}, which links libtorch, "
                 f"without {' '.join(wrong)} (common/pinned_kernels.h) in its environment")
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

named_volumes = compose.get("volumes") or {}

def mounts(service):
    return compose_mounts.mounts(compose, service)

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

# Alertmanager reads deploy/alertmanager/alertmanager.yml from the read-only mount of its
# directory, keeps its state (silences, notifications sent) in a named volume, and runs alone.
bind_ro("alertmanager", "deploy/alertmanager", "/etc/alertmanager")
alertmanager_command = services["alertmanager"].get("command") or []
config_file = flag(alertmanager_command, "config.file")
if config_file != "/etc/alertmanager/alertmanager.yml":
    fail(f"docker-compose.yml: alertmanager --config.file={config_file}, want "
         "/etc/alertmanager/alertmanager.yml")
storage = flag(alertmanager_command, "storage.path")
if not any(kind == "volume" and source in named_volumes and target == storage
           for kind, source, target, _ in mounts("alertmanager")):
    fail(f"docker-compose.yml: alertmanager's --storage.path {storage} is not a named volume")
if flag(alertmanager_command, "cluster.listen-address") != "":
    fail("docker-compose.yml: alertmanager does not set --cluster.listen-address= (empty): one "
         "instance needs no gossip, which would listen on 9094 and wait for peers")

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
# The rules' jobs are named coordinator, learner and actor (deploy/prometheus/rules.yml).
if set(jobs) != {"coordinator", "learner", "actor"}:
    fail(f"deploy/prometheus/compose.yml: jobs {sorted(jobs)}, want coordinator, learner, actor "
         "(the names rules.yml and the dashboards select)")
# Alerts go to the alertmanager service, at the port it listens on (its default, 9093, which
# it publishes).
alertmanagers = [target
                 for alertmanager in (prometheus.get("alerting") or {}).get("alertmanagers") or []
                 for static in alertmanager.get("static_configs") or []
                 for target in static.get("targets") or []]
alertmanager_port = flag(alertmanager_command, "web.listen-address") or ":9093"
if alertmanagers != [f"alertmanager{alertmanager_port}"]:
    fail(f"deploy/prometheus/compose.yml sends alerts to {alertmanagers}, want "
         f"['alertmanager{alertmanager_port}'] (docker-compose.yml's alertmanager)")
EOF

# --- docker-compose.tls.yml, merged with docker-compose.yml as it is used -------------------
tls=(docker-compose -f docker-compose.yml -f docker-compose.tls.yml)
step "docker-compose.tls.yml requires DCS_TLS_DIR"
if out=$(env -u DCS_TLS_DIR "${tls[@]}" config -q 2>&1) || [[ "$out" != *DCS_TLS_DIR* ]]; then
  fail "docker-compose.tls.yml starts without DCS_TLS_DIR (the services would have no" \
    "certificates): ${out:-no error}"
fi
# Only named, not read: config does not look at a bind mount's source. The server name is
# checked at its default.
export DCS_TLS_DIR=/check-compose/certificates
unset DCS_TLS_SERVER_NAME
step "docker-compose config -q docker-compose.yml docker-compose.tls.yml"
if ! out=$("${tls[@]}" config -q 2>&1); then
  fail "docker-compose refuses docker-compose.yml with docker-compose.tls.yml: $out"
fi
if docker compose version >/dev/null 2>&1; then
  step "docker compose config -q docker-compose.yml docker-compose.tls.yml"
  if ! out=$(docker compose -f docker-compose.yml -f docker-compose.tls.yml config -q 2>&1); then
    fail "docker compose (v2) refuses docker-compose.yml with docker-compose.tls.yml: $out"
  fi
fi
image_uid=$(sed -nE 's/.*useradd .*--uid ([0-9]+).*/\1/p' Dockerfile)
step "docker-compose.tls.yml: a one-shot copy for uid $image_uid; every DCS service's files," \
  "variables, healthcheck and start-up order"
RESOLVED="$("${tls[@]}" config)" IMAGE_UID="$image_uid" python3 - <<'EOF' || exit 1
import os
import sys

import yaml

sys.path.insert(0, "tests/deploy")
import compose_mounts  # noqa: E402

def fail(message):
    print(f"check_compose: FAIL: docker-compose.tls.yml: {message}", file=sys.stderr)
    sys.exit(1)

compose = yaml.safe_load(os.environ["RESOLVED"])
services = compose.get("services", {})
named_volumes = compose.get("volumes") or {}
uid = os.environ["IMAGE_UID"]
if not uid.isdigit():
    fail("no `useradd --uid N` in the Dockerfile: whose should the copies be?")

def mounts(service):
    """(source, target, read_only) of every mount."""
    return [(source, target, ro)
            for _, source, target, ro in compose_mounts.mounts(compose, service)]

# The one-shot copy: the only service that mounts $DCS_TLS_DIR, read-only. It runs as root, to
# read the host's keys (mode 0600, the host user's) and give the copies to the image's user,
# and writes them into a named volume.
copiers = [name for name in services
           if any(source == os.environ["DCS_TLS_DIR"] for source, _, _ in mounts(name))]
if copiers != ["tls"]:
    fail(f"want one service 'tls' mounting $DCS_TLS_DIR, found {copiers}")
copier = services["tls"]
if not all(ro for source, _, ro in mounts("tls") if source == os.environ["DCS_TLS_DIR"]):
    fail("tls mounts $DCS_TLS_DIR writable, want :ro")
if str(copier.get("user", "")).split(":")[0] not in ("0", "root"):
    fail(f"tls runs as user {copier.get('user')!r}, want root: uid {uid} could neither read "
         "the host's keys of mode 0600 nor give the copies away")
if copier.get("restart", "no") != "no":
    fail(f"tls restarts ({copier['restart']}): it is a one-shot copy")
script = " ".join(str(part) for part in copier.get("command") or [])
install = f"install -o {uid} -g {uid} -m 0400"
if install not in script:
    fail(f"tls does not copy with `{install}` (the image's user, read-only): {script!r}")
written = [(source, target) for source, target, ro in mounts("tls")
           if source in named_volumes and not ro]
if len(written) != 1:
    fail(f"tls writes into {len(written)} named volumes, want 1")
volume, copied_to = written[0]

# Every DCS service: the variables, naming the files tls copies, in that volume mounted
# read-only where tls wrote it, and the name scripts/make-certs gives by default; started only
# once tls has succeeded; healthchecks `dcs health`, which reads the same variables (no --tls
# flag of theirs may override them).
dcs = [name for name, s in services.items() if (s.get("command") or [""])[0].startswith("dcs-")]
if sorted(dcs) != ["actor", "coordinator", "learner"]:
    fail(f"DCS services are {sorted(dcs)} once merged, want actor, coordinator, learner")
files = {"DCS_TLS_CERT": "node.pem", "DCS_TLS_KEY": "node.key", "DCS_TLS_CA": "ca.pem"}
for file_name in files.values():
    if file_name not in script:
        fail(f"tls does not copy {file_name}")
for name in dcs:
    service = services[name]
    environment = service.get("environment") or {}
    for variable, file_name in files.items():
        if environment.get(variable) != f"{copied_to}/{file_name}":
            fail(f"service '{name}': {variable} is {environment.get(variable)!r}, want "
                 f"{copied_to}/{file_name}, which tls copies")
    if environment.get("DCS_TLS_SERVER_NAME") != "server.dcs":
        fail(f"service '{name}': DCS_TLS_SERVER_NAME is "
             f"{environment.get('DCS_TLS_SERVER_NAME')!r}, want server.dcs (scripts/make-certs' "
             "default): actors dial learners at container names no certificate names")
    if not environment.get("DCS_TOKEN"):
        fail(f"service '{name}' lost DCS_TOKEN in the merge")
    if (volume, copied_to, True) not in mounts(name):
        fail(f"service '{name}' does not mount the volume '{volume}' read-only at {copied_to}")
    condition = ((service.get("depends_on") or {}).get("tls") or {}).get("condition")
    if condition != "service_completed_successfully":
        fail(f"service '{name}' does not wait for tls with condition "
             f"service_completed_successfully (has {condition!r})")
    test = (service.get("healthcheck") or {}).get("test") or []
    if test[:2] != ["CMD", "dcs"] or "health" not in test or \
            any(str(arg).startswith("--tls") for arg in test):
        fail(f"service '{name}': healthcheck {test!r} is not `dcs ... health` reading DCS_TLS_*")
EOF

# --- Dockerfile: two stages, non-root, tini (grep: hadolint is not packaged) ---------------
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
