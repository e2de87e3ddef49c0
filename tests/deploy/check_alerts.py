#!/usr/bin/env python3
"""Checks the alerts of deploy/prometheus/rules.yml against docs/runbooks.md and
deploy/alertmanager/alertmanager.yml, which promtool and amtool do not relate:

- every alert has a severity (critical or warning), a summary, a description, and a
  runbook_url docs/runbooks.md#ANCHOR whose anchor is a section of docs/runbooks.md;
- every section (## heading) of docs/runbooks.md is an alert's;
- every alert name the Alertmanager config matches (routes, inhibitions) is an alert's.

    tests/deploy/check_alerts.py REPO_ROOT

Prints what it checked; exits 1 naming every problem found.
"""
import os
import re
import sys

import yaml

RULES = "deploy/prometheus/rules.yml"
RUNBOOKS = "docs/runbooks.md"
ALERTMANAGER = "deploy/alertmanager/alertmanager.yml"
SEVERITIES = {"critical", "warning"}


def anchor(heading):
    """The anchor GitHub and GitLab give a Markdown heading."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def alert_names(matchers):
    """Alert names an Alertmanager matcher list names: alertname="X" or alertname=~"X|Y"."""
    names = []
    for matcher in matchers or []:
        match = re.fullmatch(r'\s*alertname\s*(=~|=)\s*"?([^"]*)"?\s*', matcher)
        if match:
            names += match.group(2).split("|") if match.group(1) == "=~" else [match.group(2)]
    return names


def routes(route):
    yield route
    for child in route.get("routes") or []:
        yield from routes(child)


def main(root):
    os.chdir(root)
    problems = []
    with open(RULES) as f:
        rules = yaml.safe_load(f)
    alerts = {rule["alert"]: rule for group in rules["groups"] for rule in group["rules"]
              if "alert" in rule}
    with open(RUNBOOKS) as f:
        sections = [anchor(line[3:]) for line in f if line.startswith("## ")]

    for name, rule in alerts.items():
        severity = (rule.get("labels") or {}).get("severity")
        if severity not in SEVERITIES:
            problems.append(f"{RULES}: {name}: severity {severity!r}, want one of "
                            f"{sorted(SEVERITIES)}")
        annotations = rule.get("annotations") or {}
        for key in ("summary", "description"):
            if not annotations.get(key):
                problems.append(f"{RULES}: {name}: no {key} annotation")
        url = annotations.get("runbook_url", "")
        page, _, section = url.partition("#")
        if page != RUNBOOKS or not section:
            problems.append(f"{RULES}: {name}: runbook_url {url!r} is not {RUNBOOKS}#ANCHOR")
        elif section not in sections:
            problems.append(f"{RULES}: {name}: runbook_url {url!r}: {RUNBOOKS} has no section "
                            f"with anchor #{section}")
    linked = {(alerts[name].get("annotations") or {}).get("runbook_url", "").partition("#")[2]
              for name in alerts}
    for section in sections:
        if section not in linked:
            problems.append(f"{RUNBOOKS}: section #{section} is no alert's runbook_url")

    with open(ALERTMANAGER) as f:
        alertmanager = yaml.safe_load(f)
    named = []
    for route in routes(alertmanager["route"]):
        named += alert_names(route.get("matchers"))
    for rule in alertmanager.get("inhibit_rules") or []:
        named += alert_names(rule.get("source_matchers")) + alert_names(rule.get("target_matchers"))
    for name in named:
        if name not in alerts:
            problems.append(f"{ALERTMANAGER}: matches alert {name!r}, which {RULES} lacks")

    for problem in problems:
        print(f"check_alerts: FAIL: {problem}", file=sys.stderr)
    if problems:
        return 1
    print(f"check_alerts: {len(alerts)} alerts, each with a severity, a summary, a description "
          f"and its section of {RUNBOOKS}; {len(sections)} sections, each an alert's; "
          f"{len(set(named))} alert names in {ALERTMANAGER}, each an alert's")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: check_alerts.py REPO_ROOT")
    sys.exit(main(sys.argv[1]))
