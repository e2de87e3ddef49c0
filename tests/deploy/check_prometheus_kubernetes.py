#!/usr/bin/env python3
"""Checks deploy/prometheus/kubernetes.yml with Debian's Prometheus, which is built without
Kubernetes service discovery: the config is run with its kubernetes_sd_configs replaced by
static targets carrying the meta labels Kubernetes would give the pods of deploy/kubernetes's
base (their labels and annotations as written there), plus a pod of another application and a
pod without annotations. `promtool check config` must accept the copy, and a real Prometheus
must give each DCS pod the job of its component at its annotated port, leave the other
application's pod in kubernetes-pods and drop the unannotated one (read from its targets API:
the targets need not answer).

    tests/deploy/check_prometheus_kubernetes.py REPO_ROOT

Exits 1 naming the first problem.
"""
import json
import os
import re
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request

import yaml

CONFIG = "deploy/prometheus/kubernetes.yml"
WORKLOADS = "deploy/kubernetes/base"


def fail(message):
    print(f"check_prometheus_kubernetes: FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def meta(kind, name):
    """A Kubernetes label or annotation as a __meta_kubernetes_pod_* label name."""
    return f"__meta_kubernetes_pod_{kind}_" + re.sub(r"[^a-zA-Z0-9_]", "_", name)


def pod(ip, name, labels, annotations):
    """A static target as Kubernetes's pod discovery gives one: a container port of the pod."""
    target = {"__meta_kubernetes_namespace": "dcs", "__meta_kubernetes_pod_name": name}
    for key, value in labels.items():
        target[meta("label", key)] = value
    for key, value in annotations.items():
        target[meta("annotation", key)] = value
    return {"targets": [f"{ip}:50051"], "labels": target}


def dcs_pods():
    """(component, metrics port, static target) of every workload of the base."""
    pods = []
    for file_name in sorted(os.listdir(WORKLOADS)):
        if not file_name.endswith(".yaml"):
            continue
        with open(os.path.join(WORKLOADS, file_name)) as f:
            for document in yaml.safe_load_all(f):
                if not document or document.get("kind") not in ("StatefulSet", "Deployment"):
                    continue
                template = document["spec"]["template"]["metadata"]
                ip = f"10.0.0.{len(pods) + 1}"
                pods.append((template["labels"]["app.kubernetes.io/component"],
                             template["annotations"]["prometheus.io/port"],
                             pod(ip, document["metadata"]["name"], template["labels"],
                                 template.get("annotations") or {})))
    return pods


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def main(root):
    os.chdir(root)
    with open(CONFIG) as f:
        config = yaml.safe_load(f)
    jobs = [job for job in config["scrape_configs"] if job.get("kubernetes_sd_configs")]
    if [job["job_name"] for job in jobs] != ["kubernetes-pods"]:
        fail(f"{CONFIG}: want one job with kubernetes_sd_configs, kubernetes-pods")
    pods = dcs_pods()
    if sorted(component for component, _, _ in pods) != ["actor", "coordinator", "learner"]:
        fail(f"{WORKLOADS}: workloads' components are {[c for c, _, _ in pods]}")
    other = pod("10.0.1.1", "other", {"app.kubernetes.io/component": "coordinator",
                                       "app.kubernetes.io/part-of": "other"},
                {"prometheus.io/scrape": "true", "prometheus.io/port": "8080"})
    hidden = pod("10.0.1.2", "hidden", {"app.kubernetes.io/part-of": "dcs"}, {})
    job = jobs[0]
    del job["kubernetes_sd_configs"]
    job["static_configs"] = [target for _, _, target in pods] + [other, hidden]
    config["rule_files"] = [os.path.abspath(os.path.join(os.path.dirname(CONFIG), rules))
                            for rules in config.get("rule_files") or []]

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "prometheus.yml")
        with open(path, "w") as f:
            yaml.safe_dump(config, f)
        checked = subprocess.run(["promtool", "check", "config", path], capture_output=True,
                                 text=True)
        if checked.returncode != 0:
            fail(f"promtool check config ({CONFIG}, static targets): {checked.stdout}"
                 f"{checked.stderr}")
        web = f"127.0.0.1:{free_port()}"
        with open(os.path.join(tmp, "prometheus.log"), "w") as log:
            prometheus = subprocess.Popen(
                ["prometheus", f"--config.file={path}", f"--storage.tsdb.path={tmp}/tsdb",
                 f"--web.listen-address={web}"], stdout=log, stderr=log)
        try:
            targets = None
            deadline = time.monotonic() + 60
            while time.monotonic() < deadline:
                try:
                    with urllib.request.urlopen(f"http://{web}/api/v1/targets", timeout=2) as r:
                        active = json.load(r)["data"]["activeTargets"]
                    if len(active) >= 4:
                        targets = {t["labels"]["pod"]: t["labels"] for t in active}
                        break
                except OSError:
                    pass
                time.sleep(0.25)
            if targets is None:
                with open(os.path.join(tmp, "prometheus.log")) as log:
                    fail(f"Prometheus listed no 4 targets within 60 s: {log.read()[-2000:]}")
        finally:
            prometheus.terminate()
            prometheus.wait(timeout=30)

    for component, port, target in pods:
        name = target["labels"]["__meta_kubernetes_pod_name"]
        labels = targets.get(name)
        if labels is None:
            fail(f"{CONFIG} drops {name}, annotated prometheus.io/scrape")
        ip = target["targets"][0].split(":")[0]
        if labels.get("job") != component or labels.get("instance") != f"{ip}:{port}":
            fail(f"{CONFIG} scrapes {name} as job {labels.get('job')!r} at "
                 f"{labels.get('instance')!r}: want job {component!r} at {ip}:{port}")
    if (targets.get("other") or {}).get("job") != "kubernetes-pods":
        fail(f"{CONFIG}: another application's pod gets job "
             f"{(targets.get('other') or {}).get('job')!r}, want kubernetes-pods")
    if "hidden" in targets:
        fail(f"{CONFIG} scrapes a pod without prometheus.io/scrape")
    print(f"check_prometheus_kubernetes: {CONFIG}: "
          + ", ".join(f"{target['labels']['__meta_kubernetes_pod_name']} as job {component}"
                      for component, _, target in pods)
          + "; another application's pod kept in kubernetes-pods, an unannotated one dropped")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: check_prometheus_kubernetes.py REPO_ROOT")
    sys.exit(main(sys.argv[1]))
