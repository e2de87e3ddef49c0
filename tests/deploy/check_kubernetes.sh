#!/usr/bin/env bash
# Checks deploy/kubernetes without a cluster: renders every
# overlay with `kubectl kustomize`, validates every object against the Kubernetes 1.33 API
# schema (tests/deploy/kubernetes_schema/validate.js: types and values, and unknown fields),
# and checks what DCS needs of the manifests (resources, probes and ports against the programs'
# config files, the coordinator's volume, Services, disruption budgets, scrape annotations,
# mutual TLS in overlays/cluster and none in overlays/local, Alertmanager with the config of
# deploy/alertmanager where deploy/prometheus/kubernetes.yml sends the alerts).
# `kubectl apply --dry-run=client` is no substitute: it needs an API server.
#
#   tests/deploy/check_kubernetes.sh REPO_ROOT
#
# Environment:
#   KUBECTL        the kubectl to render with (default: kubectl on PATH)
#   KUBECTL_EXTRA  more kubectl binaries to render with too, space-separated (e.g. Debian 12's
#                  kubectl 1.20 beside a newer one: the manifests must suit both)
#   DCS_NPM_CACHE  where `npm ci` installs validate.js's packages, once per package-lock.json
#                  (default: ~/.cache/dcs/kubernetes-schema); never the source tree
#
# Prints each check; exits 1 at the first that fails, naming the file, object and problem.
set -euo pipefail

root=${1:?usage: check_kubernetes.sh REPO_ROOT}
cd "$root"

fail() {
  echo "check_kubernetes: FAIL: $*" >&2
  exit 1
}
step() {
  echo "check_kubernetes: $*"
}
need() {
  command -v "$1" >/dev/null 2>&1 || fail "$1 is not installed (Debian package $2; scripts/bootstrap installs it)"
}

need "${KUBECTL:-kubectl}" kubernetes-client
need node nodejs
need npm npm
need python3 python3
python3 -c 'import yaml' 2>/dev/null || fail "python3's yaml module is missing (Debian package python3-yaml)"

kubernetes=deploy/kubernetes
schema=tests/deploy/kubernetes_schema
[ -f "$kubernetes/base/kustomization.yaml" ] || fail "$kubernetes/base/kustomization.yaml is missing"
overlays=()
for dir in "$kubernetes"/overlays/*/; do
  [ -f "$dir/kustomization.yaml" ] && overlays+=("${dir%/}")
done
[ ${#overlays[@]} -gt 0 ] || fail "no overlay with a kustomization.yaml under $kubernetes/overlays/"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# --- validate.js's npm packages, installed once per lock file, outside the source tree ------
lock_hash=$(cat "$schema/package.json" "$schema/package-lock.json" | sha256sum | cut -c1-16)
modules=${DCS_NPM_CACHE:-${XDG_CACHE_HOME:-${HOME:-/tmp}/.cache}/dcs/kubernetes-schema}/$lock_hash
if [ ! -f "$modules/node_modules/.dcs-installed" ]; then
  step "npm ci $schema (kubernetes-models, typescript) into $modules"
  mkdir -p "$(dirname "$modules")"
  staging=$(mktemp -d "$modules.XXXXXX")
  cp "$schema/package.json" "$schema/package-lock.json" "$staging/"
  if ! (cd "$staging" && npm ci --no-audit --no-fund --loglevel=error >npm.log 2>&1); then
    log=$(tail -20 "$staging/npm.log")
    rm -rf "$staging"
    fail "npm ci in $schema failed: $log"
  fi
  touch "$staging/node_modules/.dcs-installed"
  # Another run may have installed it meanwhile (either copy will do); a directory without
  # the mark is a failed attempt.
  [ -f "$modules/node_modules/.dcs-installed" ] || rm -rf "$modules"
  if ! mv -T "$staging" "$modules" 2>/dev/null; then rm -rf "$staging"; fi
  [ -f "$modules/node_modules/.dcs-installed" ] || fail "cannot install into $modules"
fi

# --- render every overlay with every kubectl --------------------------------------------
# kustomize v5 warns that `bases`, `patchesStrategicMerge` and `patchesJson6902` are
# deprecated; they stay for Debian's kubectl 1.20 (deploy/kubernetes/base/kustomization.yaml),
# so those warnings are expected. Any other word on stderr is shown.
rendered=()
for kubectl in ${KUBECTL:-kubectl} ${KUBECTL_EXTRA:-}; do
  command -v "$kubectl" >/dev/null 2>&1 || fail "$kubectl (KUBECTL, KUBECTL_EXTRA) is not a program"
  version=$("$kubectl" version --client -o json 2>/dev/null \
              | python3 -c 'import json, sys; print(json.load(sys.stdin)["clientVersion"]["gitVersion"])') \
    || fail "$kubectl version --client fails"
  for overlay in "${overlays[@]}"; do
    step "kubectl $version kustomize $overlay"
    out="$tmp/$(basename "$overlay")-$version.yaml"
    status=0
    "$kubectl" kustomize "$overlay" >"$out" 2>"$tmp/stderr" || status=$?
    said=$(grep -vE "^# Warning: '(bases|patchesStrategicMerge|patchesJson6902)' is deprecated" \
             "$tmp/stderr" || true)
    [ "$status" -eq 0 ] || fail "kubectl $version kustomize $overlay: $said"
    [ -z "$said" ] || echo "$said" >&2
    rendered+=("$out")
  done
done

# --- every object against the Kubernetes API schema -------------------------------------
for file in "${rendered[@]}"; do
  python3 -c 'import json, sys, yaml
json.dump([d for d in yaml.safe_load_all(open(sys.argv[1])) if d is not None], open(sys.argv[2], "w"))' \
    "$file" "${file%.yaml}.json" || fail "$file: not YAML"
done
step "validate.js: every object against the Kubernetes 1.33 API schema, unknown fields refused"
if ! out=$(NODE_PATH="$modules/node_modules" node "$schema/validate.js" "${rendered[@]/%.yaml/.json}" 2>&1); then
  fail "${out//$tmp\//}"
fi
step "${out//$tmp\//}"

# --- what DCS needs of the manifests ----------------------------------------------------
step "DCS: kinds, coordinator StatefulSet and volume, Deployments, probes and ports against the config files, resources, Services, PodDisruptionBudgets, scrape annotations, security, mutual TLS, pinned kernels, Alertmanager"
python3 - "${rendered[@]}" <<'EOF' || exit 1
import os
import re
import sys

import yaml

sys.path.insert(0, "tests/deploy")
from command_flags import flag  # noqa: E402
from pinned_kernels import torch_programs, unpinned  # noqa: E402

files = sys.argv[1:]

# Kinds this deployment uses, each served by Kubernetes 1.24 and later (grpc probes: 1.24,
# on by default; GA in 1.27). kubernetes-models also carries removed versions (policy/v1beta1,
# extensions/v1beta1), so validate.js alone would let them through.
KINDS = {("v1", "ConfigMap"), ("v1", "Service"),
         ("apps/v1", "StatefulSet"), ("apps/v1", "Deployment"),
         ("policy/v1", "PodDisruptionBudget")}
# The gRPC health names each program serves (services/server.cc sets "" and every served
# service alike; the services: coordinator_main.cc, learner/learner_main.cc; the actor serves
# none of its own). Any other name answers NOT_FOUND, and the probe never succeeds.
HEALTH_NAMES = {"dcs-coordinator": {"", "dcs.v1.CoordinatorService"},
                "dcs-learner": {"", "dcs.v1.LearnerService"},
                "dcs-actor": {""}}
# The overlays with mutual TLS (overlays/cluster/tls.yaml); any other is token-only.
TLS_OVERLAYS = {"cluster"}
# Where each DCS_TLS_* variable's file comes from: keys of the Secret dcs-tls, as cert-manager
# writes them.
TLS_KEYS = {"DCS_TLS_CERT": "tls.crt", "DCS_TLS_KEY": "tls.key", "DCS_TLS_CA": "ca.crt"}
LABELS = ("app.kubernetes.io/name", "app.kubernetes.io/instance", "app.kubernetes.io/part-of",
          "app.kubernetes.io/managed-by")
UNITS = {"": 1, "m": 1e-3, "k": 1e3, "M": 1e6, "G": 1e9, "T": 1e12,
         "Ki": 2**10, "Mi": 2**20, "Gi": 2**30, "Ti": 2**40}


def quantity(value):
    match = re.fullmatch(r"([0-9.]+)([a-zA-Z]*)", str(value))
    if not match or match.group(2) not in UNITS:
        return None
    return float(match.group(1)) * UNITS[match.group(2)]


def seconds(value):
    match = re.fullmatch(r"([0-9.]+)(ms|s|m|h)", str(value))
    return float(match.group(1)) * {"ms": 1e-3, "s": 1, "m": 60, "h": 3600}[match.group(2)]


def port_of(address):
    match = re.fullmatch(r"(.*):(\d+)", str(address or ""))
    return (match.group(1), int(match.group(2))) if match else (None, None)


def matches(selector, labels):
    return bool(selector) and all(labels.get(k) == v for k, v in selector.items())


def check_alertmanager(w, configmaps, fail):
    """Checks the Alertmanager Deployment; returns it with its ports, as the Services need."""
    where = "Deployment/dcs-alertmanager"
    spec = w["spec"]
    pod = spec["template"]["spec"]
    if spec.get("replicas", 1) != 1:
        fail(where, f"replicas {spec['replicas']}: the config runs one Alertmanager, without "
             "the cluster gossip replicas would need")
    if not matches(spec["selector"].get("matchLabels"), spec["template"]["metadata"]["labels"]):
        fail(where, "spec.selector does not select the pod template's labels")
    if (pod.get("securityContext") or {}).get("runAsNonRoot") is not True:
        fail(where, "securityContext.runAsNonRoot is not true")
    (c,) = pod["containers"]
    with open("docker-compose.yml") as f:
        pinned = yaml.safe_load(f)["services"]["alertmanager"]["image"]
    if c["image"] != pinned:
        fail(where, f"image {c['image']}, but docker-compose.yml pins {pinned}: one version")
    context = c.get("securityContext") or {}
    if context.get("readOnlyRootFilesystem") is not True or \
            context.get("allowPrivilegeEscalation") is not False:
        fail(where, "securityContext: want readOnlyRootFilesystem true, "
             "allowPrivilegeEscalation false")
    resources = c.get("resources") or {}
    for kind in ("requests", "limits"):
        for resource in ("cpu", "memory"):
            if quantity((resources.get(kind) or {}).get(resource)) is None:
                fail(where, f"resources.{kind}.{resource} is missing or not a quantity")
    args = c.get("args") or []
    if flag(args, "cluster.listen-address") != "":
        fail(where, "no --cluster.listen-address= (empty): one Alertmanager needs no gossip")
    volumes = {v["name"]: v for v in pod.get("volumes") or []}
    mounts = {m["mountPath"]: m["name"] for m in c.get("volumeMounts") or []}
    storage = volumes.get(mounts.get(flag(args, "storage.path")), {})
    if "emptyDir" not in storage and "persistentVolumeClaim" not in storage:
        fail(where, f"--storage.path={flag(args, 'storage.path')} is on no writable volume "
             "(the root file system is read-only)")
    # Its config is deploy/alertmanager/alertmanager.yml, as compose mounts it.
    directory, file_name = os.path.split(flag(args, "config.file") or "")
    configmap = configmaps.get((volumes.get(mounts.get(directory), {}).get("configMap") or {})
                               .get("name"))
    with open("deploy/alertmanager/alertmanager.yml") as f:
        wanted = f.read()
    if configmap is None or (configmap.get("data") or {}).get(file_name) != wanted:
        fail(where, f"--config.file={directory}/{file_name} is not "
             "deploy/alertmanager/alertmanager.yml from a mounted ConfigMap")
    w["_ports"] = {p["containerPort"]: p.get("name") for p in c.get("ports") or []}
    return w


rendered_overlays = set()
for path in files:
    name = os.path.basename(path)
    overlay = re.match(r"(.*?)-v[0-9]", name).group(1)  # <overlay>-<kubectl version>.yaml
    tls = overlay in TLS_OVERLAYS
    server_names = set()  # DCS_TLS_SERVER_NAME of every container

    def fail(where, message):
        print(f"check_kubernetes: FAIL: {name}: {where}: {message}", file=sys.stderr)
        sys.exit(1)

    objects = [o for o in yaml.safe_load_all(open(path)) if o]
    by_kind = {}
    for o in objects:
        by_kind.setdefault(o["kind"], []).append(o)
        where = f"{o['kind']}/{o['metadata']['name']}"
        if (o["apiVersion"], o["kind"]) not in KINDS:
            fail(where, f"apiVersion {o['apiVersion']} kind {o['kind']} is not one this "
                 f"deployment expects: {sorted(KINDS)} (add it after checking that Kubernetes "
                 "1.24 and later serve it)")
        labels = o["metadata"].get("labels") or {}
        for label in LABELS:
            if label not in labels:
                fail(where, f"no label {label}")

    def workload(kind, object_name):
        found = [o for o in by_kind.get(kind, []) if o["metadata"]["name"] == object_name]
        if not found:
            others = [f"{o['kind']}/{o['metadata']['name']}" for o in objects
                      if o["metadata"]["name"] == object_name]
            fail(f"{kind}/{object_name}", "missing" + (f" (found {others[0]})" if others else ""))
        return found[0]

    coordinator = workload("StatefulSet", "dcs-coordinator")
    workloads = [coordinator, workload("Deployment", "dcs-learner"),
                 workload("Deployment", "dcs-actor")]
    configmaps = {o["metadata"]["name"]: o for o in by_kind.get("ConfigMap", [])}
    services = by_kind.get("Service", [])
    grpc_ports = {}  # program -> its gRPC port, from its flags

    for w in workloads:
        where = f"{w['kind']}/{w['metadata']['name']}"
        template = w["spec"]["template"]
        pod = template["spec"]
        pod_labels = template["metadata"].get("labels") or {}
        if not matches(w["spec"]["selector"].get("matchLabels"), pod_labels):
            fail(where, "spec.selector does not select the pod template's labels")
        if "app.kubernetes.io/component" not in pod_labels:
            fail(where, "the pod template has no label app.kubernetes.io/component")

        security = pod.get("securityContext") or {}
        if security.get("runAsNonRoot") is not True or security.get("runAsUser") != 10001:
            fail(where, "pods must run as uid 10001 (securityContext runAsNonRoot, runAsUser)")

        volumes = {v["name"]: v for v in pod.get("volumes") or []}
        for claim in w["spec"].get("volumeClaimTemplates") or []:
            volumes[claim["metadata"]["name"]] = {"claim": claim}
        container_ports = {}
        for c in pod["containers"]:
            cwhere = f"{where}: container {c['name']}"
            ports = {p["containerPort"]: p.get("name") for p in c.get("ports") or []}
            container_ports.update(ports)
            named = {v: k for k, v in ports.items() if v}

            # Resources: requests and limits of CPU and memory, requests within limits.
            resources = c.get("resources") or {}
            for kind in ("requests", "limits"):
                for resource in ("cpu", "memory"):
                    if quantity((resources.get(kind) or {}).get(resource)) is None:
                        fail(cwhere, f"resources.{kind}.{resource} is missing or not a quantity")
            for resource in ("cpu", "memory"):
                if quantity(resources["requests"][resource]) > quantity(resources["limits"][resource]):
                    fail(cwhere, f"requests.{resource} {resources['requests'][resource]} exceeds "
                         f"limits.{resource} {resources['limits'][resource]}")

            context = c.get("securityContext") or {}
            if context.get("readOnlyRootFilesystem") is not True:
                fail(cwhere, "securityContext.readOnlyRootFilesystem is not true")
            if context.get("allowPrivilegeEscalation") is not False:
                fail(cwhere, "securityContext.allowPrivilegeEscalation is not false")
            mounts = {m["mountPath"]: m["name"] for m in c.get("volumeMounts") or []}
            for mount_path, volume in mounts.items():
                if volume not in volumes:
                    fail(cwhere, f"mounts volume '{volume}' at {mount_path}, which the pod lacks")
            if "emptyDir" not in volumes.get(mounts.get("/tmp"), {}):
                fail(cwhere, "no emptyDir at /tmp (the root file system is read-only)")

            # The program: args[0] under the image's ENTRYPOINT (tini), or a command.
            argv = list(c.get("command") or []) + list(c.get("args") or [])
            if argv and os.path.basename(argv[0]) == "tini":
                argv = argv[argv.index("--") + 1:] if "--" in argv else argv[1:]
            program = os.path.basename(argv[0]) if argv else ""
            if c is pod["containers"][0] and program != w["metadata"]["name"]:
                fail(cwhere, f"runs {program or 'nothing'!r}, want {w['metadata']['name']}")
            if program not in HEALTH_NAMES:
                continue  # not a DCS program

            # The program's flags: its --config file from the ConfigMap, then the arguments
            # (which win), with $(VAR) taken from the container's environment.
            env = {e["name"]: e for e in c.get("env") or []}
            # Every DCS program holds the cluster's one token, from the one Secret.
            secret = (env.get("DCS_TOKEN", {}).get("valueFrom") or {}).get("secretKeyRef") or {}
            if (secret.get("name"), secret.get("key")) != ("dcs-token", "token") or \
                    secret.get("optional"):
                fail(cwhere, "DCS_TOKEN is not taken from key 'token' of the Secret dcs-token "
                     "(required): the program would not hold the cluster's token")

            # Mutual TLS: the files from the Secret dcs-tls, mounted read-only, readable by the
            # program's group (fsGroup) and no other user (the files are root's); one
            # cluster-wide server name, since learners are dialled at pod IPs no certificate
            # names. Token-only overlays have none of it.
            tls_volumes = {v for v, volume in volumes.items()
                           if (volume.get("secret") or {}).get("secretName") == "dcs-tls"}
            tls_mounts = {m["mountPath"]: m for m in c.get("volumeMounts") or []
                          if m["name"] in tls_volumes}
            tls_variables = sorted(e for e in env if e.startswith("DCS_TLS_"))
            if not tls and (tls_variables or tls_mounts):
                fail(cwhere, f"has {tls_variables or 'the Secret dcs-tls'}, but overlay "
                     f"{overlay} is token-only (TLS_OVERLAYS: {sorted(TLS_OVERLAYS)})")
            for variable, key in TLS_KEYS.items() if tls else ():
                file_path = (env.get(variable) or {}).get("value")
                if file_path is None:
                    fail(cwhere, f"no {variable}: overlay {overlay} has mutual TLS")
                directory, file_name = os.path.split(file_path)
                mount = tls_mounts.get(directory)
                if mount is None:
                    fail(cwhere, f"{variable}={file_path}: the Secret dcs-tls is not mounted at "
                         f"{directory}")
                secret = volumes[mount["name"]]["secret"]
                if file_name != key or secret.get("items"):
                    fail(cwhere, f"{variable}={file_path}: want key {key} of dcs-tls, as "
                         f"{directory}/{key} (no items:)")
                if secret.get("optional") or mount.get("readOnly") is not True:
                    fail(cwhere, f"the Secret dcs-tls at {directory} is optional or not readOnly")
                mode = secret.get("defaultMode", 0o644)
                if mode & 0o047 != 0o040 or security.get("fsGroup") is None:
                    fail(cwhere, f"the Secret dcs-tls has mode {mode:04o}, fsGroup "
                         f"{security.get('fsGroup')}: its files are root's, so uid 10001 reads "
                         "them only as fsGroup; want 0440 (group-readable, no one else) and fsGroup")
            if tls:
                server_name = (env.get("DCS_TLS_SERVER_NAME") or {}).get("value")
                if not server_name:
                    fail(cwhere, "no DCS_TLS_SERVER_NAME: actors dial learners at pod IPs, "
                         "which no certificate names")
                server_names.add(server_name)

            def expand(text):
                def value(m):
                    e = env.get(m.group(1))
                    if e is None:
                        fail(cwhere, f"argument {text} names $({m.group(1)}), not in env")
                    return str(e.get("value", f"<{m.group(1)}>"))
                return re.sub(r"\$\(([A-Za-z_][A-Za-z0-9_]*)\)", value, text)
            flags = {}
            arguments = [expand(a) for a in argv[1:]]
            for a in arguments:
                if not a.startswith("--") or "=" not in a:
                    fail(cwhere, f"argument {a!r}: write flags as --name=value")
            config_path = next((a.split("=", 1)[1] for a in arguments
                                if a.startswith("--config=")), None)
            if config_path is None:
                fail(cwhere, "no --config=FILE argument")
            directory, file_name = os.path.split(config_path)
            volume = volumes.get(mounts.get(directory), {})
            configmap = configmaps.get((volume.get("configMap") or {}).get("name"))
            if configmap is None or file_name not in (configmap.get("data") or {}):
                fail(cwhere, f"--config={config_path}: no ConfigMap holding {file_name} is "
                     f"mounted at {directory}")
            for key, value in (yaml.safe_load(configmap["data"][file_name]) or {}).items():
                flags[key.replace("-", "_")] = str(value)
            for a in arguments:
                key, value = a[2:].split("=", 1)
                flags[key.replace("-", "_")] = value

            host, grpc_port = port_of(flags.get("listen"))
            metrics_host, metrics_port = port_of(flags.get("metrics_listen"))
            if host != "0.0.0.0" or not grpc_port:
                fail(cwhere, f"{program} listens on {flags.get('listen')!r}: want 0.0.0.0:PORT "
                     f"(in {file_name} or the arguments)")
            if metrics_host != "0.0.0.0" or not metrics_port:
                fail(cwhere, f"{program} serves metrics on {flags.get('metrics_listen')!r}: want "
                     "0.0.0.0:PORT")
            for port, what in ((grpc_port, "gRPC"), (metrics_port, "metrics")):
                if port not in ports:
                    fail(cwhere, f"{program}'s {what} port {port} ({file_name}) is not a "
                         f"containerPort (has {sorted(ports)})")
            grpc_ports[program] = grpc_port
            if flags.get("log_format") != "json":
                fail(cwhere, f"{program} logs as {flags.get('log_format', 'text')!r}, want json")
            grace = pod.get("terminationGracePeriodSeconds", 30)
            if seconds(flags.get("shutdown_grace", "3s")) >= grace:
                fail(cwhere, f"shutdown_grace {flags.get('shutdown_grace')} does not fit in "
                     f"terminationGracePeriodSeconds {grace}")

            # Probes: ready = gRPC health on the program's port, by a name it serves. Kubelet
            # asks it itself (grpc), in plaintext only; under mutual TLS the program refuses
            # plaintext, so the probe runs `dcs health` (exec), which reads DCS_TLS_*.
            def health(probe_name):
                """Checks a probe of the program's health; False if it is another probe."""
                probe = c.get(probe_name) or {}
                if "grpc" in probe:
                    if tls:
                        fail(cwhere, f"{probe_name} is grpc, in plaintext, which {program} "
                             "refuses under mutual TLS: exec `dcs --timeout=2s health "
                             "--addr=127.0.0.1:PORT`, which reads DCS_TLS_*")
                    port, service = probe["grpc"].get("port"), probe["grpc"].get("service", "")
                elif "exec" in probe:
                    command = [str(a) for a in probe["exec"].get("command") or []]
                    if not tls:
                        fail(cwhere, f"{probe_name} runs {command}: without TLS, probe grpc "
                             "(kubelet asks itself, no process)")
                    if not command or os.path.basename(command[0]) != "dcs" or \
                            "health" not in command:
                        fail(cwhere, f"{probe_name} runs {command}, not `dcs ... health`")
                    addr = flag(command, "addr")
                    host, port = port_of(addr)
                    if host not in ("127.0.0.1", "localhost"):
                        fail(cwhere, f"{probe_name}: `dcs health --addr={addr}`, want "
                             "127.0.0.1:PORT, the container's own server")
                    service = flag(command, "service") or ""
                    timeout = flag(command, "timeout")
                    if timeout is None or seconds(timeout) >= probe.get("timeoutSeconds", 1):
                        fail(cwhere, f"{probe_name}: `dcs health --timeout={timeout}` does not "
                             f"end within timeoutSeconds {probe.get('timeoutSeconds', 1)}")
                else:
                    return False
                if port != grpc_port:
                    fail(cwhere, f"{probe_name} asks port {port}, but {program} listens on "
                         f"{grpc_port}")
                if service not in HEALTH_NAMES[program]:
                    fail(cwhere, f"{probe_name} asks for health of {service!r}, which {program} "
                         f"does not serve (it serves {sorted(HEALTH_NAMES[program])})")
                return True

            if not health("readinessProbe"):
                fail(cwhere, "no readinessProbe of gRPC health (grpc; exec `dcs health` under TLS)")
            for probe_name in ("livenessProbe", "startupProbe"):
                probe = c.get(probe_name)
                if probe is None:
                    if probe_name == "livenessProbe":
                        fail(cwhere, "no livenessProbe")
                    continue
                if health(probe_name):
                    continue
                if "httpGet" in probe:
                    http = probe["httpGet"]
                    port = named.get(http.get("port"), http.get("port"))
                    if port != metrics_port or http.get("path") != "/metrics":
                        fail(cwhere, f"{probe_name} gets {http.get('path')} on port "
                             f"{http.get('port')}; the only HTTP endpoint is /metrics on "
                             f"{metrics_port}")
                else:
                    fail(cwhere, f"{probe_name} is neither gRPC health nor httpGet /metrics")
            liveness_is_health = health("livenessProbe")
            if program == "dcs-coordinator" and not liveness_is_health:
                fail(cwhere, "the coordinator's livenessProbe is not gRPC health")
            if program != "dcs-coordinator" and liveness_is_health:
                fail(cwhere, "a worker's livenessProbe must not be gRPC health: a worker is SERVING "
                     "only while registered with the coordinator (every health name, \"\" "
                     "included), so it would be restarted whenever the coordinator is "
                     "unreachable; probe httpGet /metrics instead")

            if program == "dcs-coordinator":
                data_dir = flags.get("data_dir")
                volume = volumes.get(mounts.get(data_dir), {})
                if "claim" not in volume:
                    fail(cwhere, f"--data-dir {data_dir} is not on a volumeClaimTemplate")
                if "ReadWriteOnce" not in volume["claim"]["spec"].get("accessModes", []):
                    fail(cwhere, "the data volume is not ReadWriteOnce")
            else:
                # Workers: reachable at the pod IP, and dial the coordinator's Service.
                if flags.get("advertise_host") != "<POD_IP>" or \
                        (env.get("POD_IP", {}).get("valueFrom", {}).get("fieldRef", {})
                         .get("fieldPath")) != "status.podIP":
                    fail(cwhere, "--advertise-host is not $(POD_IP) with POD_IP from "
                         "status.podIP: other pods could not reach this worker")
                flags_coordinator = flags.get("coordinator")
                host, port = port_of(flags_coordinator)
                service = next((s for s in services if s["metadata"]["name"] == host), None)
                if service is None or not matches(
                        service["spec"].get("selector"),
                        coordinator["spec"]["template"]["metadata"]["labels"]) \
                        or port not in [p["port"] for p in service["spec"]["ports"]]:
                    fail(cwhere, f"--coordinator {flags_coordinator} is not a port of a Service "
                         "in front of the coordinator")
            # A program that links libtorch starts with the pinned numeric kernels, or it starts
            # libtorch, finds them unset and runs itself again with them.
            if program in torch_programs():
                wrong = unpinned({n: e.get("value") for n, e in env.items()})
                if wrong:
                    fail(cwhere, f"{program} links libtorch, but its env lacks "
                         f"{' '.join(wrong)} (common/pinned_kernels.h)")
            if program == "dcs-learner":
                if env.get("OMP_NUM_THREADS", {}).get("value") != "1":
                    fail(cwhere, "OMP_NUM_THREADS is not 1 (libtorch)")
                cpus = quantity(resources["limits"]["cpu"])
                max_runs = flags.get("max_runs", "")
                if not max_runs.isdigit() or int(max_runs) != round(2 * cpus):
                    fail(cwhere, f"--max-runs is {max_runs or 'unset'}, want twice the CPU limit "
                         f"{resources['limits']['cpu']}: {round(2 * cpus)} (dcs-learner's default "
                         "counts the node's cores, not the pod's)")

        # Scrape annotations name a port the pod serves metrics on.
        annotations = template["metadata"].get("annotations") or {}
        if annotations.get("prometheus.io/scrape") != "true":
            fail(where, "the pod template lacks prometheus.io/scrape: \"true\"")
        if annotations.get("prometheus.io/path") != "/metrics":
            fail(where, "the pod template's prometheus.io/path is not /metrics")
        scrape_port = annotations.get("prometheus.io/port", "")
        if not scrape_port.isdigit() or int(scrape_port) not in container_ports \
                or container_ports[int(scrape_port)] != "metrics":
            fail(where, f"prometheus.io/port {scrape_port!r} is not the pod's metrics port "
                 f"({[p for p, n in container_ports.items() if n == 'metrics']})")
        w["_ports"] = container_ports

    alertmanager = check_alertmanager(workload("Deployment", "dcs-alertmanager"), configmaps,
                                      fail)

    if len(server_names) > 1:
        fail("DCS_TLS_SERVER_NAME", f"differs between containers ({sorted(server_names)}): every "
             "server holds a certificate for one cluster-wide name")

    if coordinator["spec"].get("replicas", 1) != 1:
        fail("StatefulSet/dcs-coordinator", f"replicas {coordinator['spec']['replicas']}: the "
             "coordinator's SQLite store has one writer; more replicas would be more stores")
    if not coordinator["spec"].get("volumeClaimTemplates"):
        fail("StatefulSet/dcs-coordinator", "no volumeClaimTemplates (its store)")

    # Services select a workload's pods and target ports they have.
    for s in services:
        where = f"Service/{s['metadata']['name']}"
        selected = [w for w in workloads + [alertmanager]
                    if matches(s["spec"].get("selector"), w["spec"]["template"]["metadata"]["labels"])]
        if len(selected) != 1:
            fail(where, f"selects the pods of {len(selected)} workloads, want 1")
        ports = selected[0]["_ports"]
        for p in s["spec"]["ports"]:
            target = p.get("targetPort", p["port"])
            if target not in ports and target not in ports.values():
                fail(where, f"port {p['port']} targets {target!r}, which "
                     f"{selected[0]['metadata']['name']}'s pods do not have ({ports})")
    service_name = coordinator["spec"].get("serviceName")
    governing = [s for s in services if s["metadata"]["name"] == service_name]
    if not governing or governing[0]["spec"].get("clusterIP") != "None":
        fail("StatefulSet/dcs-coordinator", f"serviceName {service_name!r} is not a headless "
             "Service")

    # Disruption budgets, each for one workload's pods.
    budgets = by_kind.get("PodDisruptionBudget", [])
    if not budgets:
        fail("PodDisruptionBudget", "none")
    for b in budgets:
        where = f"PodDisruptionBudget/{b['metadata']['name']}"
        selector = b["spec"].get("selector", {}).get("matchLabels")
        selected = [w for w in workloads if matches(selector, w["spec"]["template"]["metadata"]["labels"])]
        if len(selected) != 1:
            fail(where, f"selects the pods of {len(selected)} workloads, want 1")
        if "maxUnavailable" not in b["spec"] and "minAvailable" not in b["spec"]:
            fail(where, "neither maxUnavailable nor minAvailable")

    # One image for every DCS program, with a tag (a :latest or missing tag makes Kubernetes
    # pull on every start, which fails without a registry).
    images = {c["image"] for w in workloads for c in w["spec"]["template"]["spec"]["containers"]}
    if len(images) != 1:
        fail("images", f"want one image for every DCS program, found {sorted(images)}")
    image = images.pop()
    tag = image.rsplit(":", 1)[1] if ":" in image.rsplit("/", 1)[-1] else ""
    if tag in ("", "latest") and "@" not in image:
        fail("images", f"{image} has no tag, or :latest (set one with kustomize images:)")

    # Prometheus (deploy/prometheus/kubernetes.yml) sends alerts to the Alertmanager Service.
    namespace = alertmanager["metadata"].get("namespace", "default")
    with open("deploy/prometheus/kubernetes.yml") as f:
        prometheus = yaml.safe_load(f)
    targets = [target for a in (prometheus.get("alerting") or {}).get("alertmanagers") or []
               for static in a.get("static_configs") or []
               for target in static.get("targets") or []]
    serving = [f"{s['metadata']['name']}.{namespace}.svc:{p['port']}" for s in services
               if matches(s["spec"].get("selector"),
                          alertmanager["spec"]["template"]["metadata"]["labels"])
               for p in s["spec"]["ports"]]
    if not targets or any(t not in serving for t in targets):
        fail("deploy/prometheus/kubernetes.yml", f"sends alerts to {targets}, but the Services "
             f"in front of Alertmanager are {serving}")

    security = f"mutual TLS as {server_names.pop()}" if tls else "token only"
    print(f"check_kubernetes: {name}: {len(objects)} objects as DCS needs them "
          f"(image {image}; gRPC ports {grpc_ports}; {security})")
    rendered_overlays.add(overlay)

if TLS_OVERLAYS - rendered_overlays:
    print(f"check_kubernetes: FAIL: TLS_OVERLAYS names {sorted(TLS_OVERLAYS - rendered_overlays)}, "
          f"but the overlays are {sorted(rendered_overlays)}", file=sys.stderr)
    sys.exit(1)
EOF

step "all checks passed"
