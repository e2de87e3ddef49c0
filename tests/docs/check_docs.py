#!/usr/bin/env python3
# Copyright 2026 The DCS Authors.
"""Checks that README.md and docs/*.md hold together with the repository and the client.

  1. Every relative link and image of README.md and docs/*.md names a file or folder of the
     repository, and its #anchor, if any, a heading of the Markdown file it points to (GitHub's
     anchors: the heading in lower case, punctuation dropped, spaces as hyphens).
  2. Every `dcs` command in their code blocks exists: `dcs COMMAND [SUBCOMMAND] --help`
     exits 0 and prints that command's usage (`Usage: dcs COMMAND ...`; the client prints its own
     top-level usage for a command it does not know), a subcommand is one its command's help
     lists, and a word after a command that takes no arguments is an unknown subcommand.
  3. No line is a merge's conflict marker (`<<<<<<< `, `=======`, `>>>>>>> `): a conflict
     committed unresolved renders as text, which links and commands alone would not catch.

Usage: tests/docs/check_docs.py REPO_ROOT DCS_PROGRAM
Prints every problem, one a line with its file and line; exits 1 if there is any.
"""

import pathlib
import re
import shlex
import subprocess
import sys

# `dcs`'s global options that take a value (dcs --help): they may come before the command.
GLOBAL_OPTIONS_WITH_VALUE = {"--addr", "--data-dir", "--token-file", "--tls-cert", "--tls-key",
                             "--tls-ca", "--tls-server-name", "--timeout", "-o", "--output"}
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
FENCE = re.compile(r"^\s*```")
SHELL_FENCE = re.compile(r"^\s*```(?:sh|bash|shell|console)\s*$")
# `dcs` where a shell takes a command: first on the line (after VAR=value assignments), or after
# ;, &&, || or $(.
DCS_CALL = re.compile(r"(?:^|;|&&|\|\||\$\()\s*(?:\w+=\S*\s+)*(?:\S*/)?dcs(?=\s)(.*)$")


def anchor(heading):
    """GitHub's anchor of a Markdown heading's text."""
    text = re.sub(r"`|\*\*|\*|_(?=\w)|(?<=\w)_", "", heading.strip()).lower()
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def prose_lines(path):
    """(line number, text) of `path` outside code blocks, inline code removed."""
    inside = False
    for number, line in enumerate(path.read_text(encoding="utf-8").split("\n"), 1):
        if FENCE.match(line):
            inside = not inside
            continue
        if not inside:
            yield number, re.sub(r"`[^`]*`", "", line)


def anchors_of(path):
    return {anchor(text[text.index(" ") + 1:]) for _, text in prose_lines(path)
            if re.match(r"^#{1,6} ", text)}


def check_links(repo, path, checked):
    problems = []
    for number, text in prose_lines(path):
        for target in LINK.findall(text):
            checked.append(target)
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # https:, mailto:, ...
                continue
            file_part, _, fragment = target.partition("#")
            resolved = (path.parent / file_part).resolve() if file_part else path
            where = f"{path.relative_to(repo)}:{number}: link {target}"
            if not resolved.exists():
                problems.append(f"{where}: no such file")
            elif fragment and resolved.suffix == ".md" and fragment not in anchors_of(resolved):
                problems.append(f"{where}: {resolved.relative_to(repo)} has no heading #{fragment}")
            elif not str(resolved).startswith(str(repo)):
                problems.append(f"{where}: outside the repository")
    return problems


def code_block_commands(path):
    """(line number, argument words) of each `dcs` call in `path`'s shell code blocks."""
    inside = shell = False
    pending = ""
    pending_number = 0
    for number, line in enumerate(path.read_text(encoding="utf-8").split("\n"), 1):
        if FENCE.match(line):
            inside, shell = not inside, not inside and bool(SHELL_FENCE.match(line))
            continue
        if not shell:
            continue
        if not pending:
            pending_number = number
        if line.endswith("\\"):
            pending += line[:-1] + " "
            continue
        text, pending = re.sub(r"(^|\s)#.*$", "", pending + line), ""
        match = DCS_CALL.search(text)
        if match:
            try:
                words = shlex.split(match.group(1), comments=True)
            except ValueError:
                words = match.group(1).split()
            yield pending_number, words


def subcommands(help_text):
    listed, inside = set(), False
    for line in help_text.split("\n"):
        if line.startswith("Subcommands:"):
            inside = True
        elif inside and re.match(r"^  \S", line):
            listed.add(line.split()[0])
        elif inside and line and not line.startswith(" "):
            inside = False
    return listed


def run_help(dcs, words):
    result = subprocess.run([dcs, *words, "--help"], capture_output=True, text=True, timeout=30)
    return result.returncode, result.stdout


def check_commands(repo, dcs, path, checked):
    problems = []
    for number, words in code_block_commands(path):
        i = 0
        while i < len(words) and words[i].startswith("-"):
            i += 2 if words[i] in GLOBAL_OPTIONS_WITH_VALUE else 1
        if i >= len(words):
            continue
        command = [words[i]]
        code, out = run_help(dcs, command)
        if code == 0 and i + 1 < len(words) and words[i + 1] in subcommands(out):
            command.append(words[i + 1])
            code, out = run_help(dcs, command)
        name = " ".join(command)
        checked.append(name)
        usage = re.search(rf"^Usage: \S*dcs {re.escape(name)}\b(.*)$", out, re.M)
        if code != 0 or not usage:
            problems.append(f"{path.relative_to(repo)}:{number}: `dcs {name}`: no such command "
                            f"(`dcs {name} --help` exits {code} without its usage)")
            continue
        rest = words[i + len(command):]
        takes_arguments = re.sub(r"\[OPTIONS\]|\[?SUBCOMMAND\]?", "", usage.group(1)).strip()
        if rest and not rest[0].startswith("-") and not takes_arguments:
            problems.append(f"{path.relative_to(repo)}:{number}: `dcs {name} {rest[0]}`: no such "
                            f"subcommand (`dcs {name}` takes no arguments: {usage.group(0)})")
    return problems


CONFLICT_MARKER = re.compile(r"^(<{7} |={7}$|>{7} )")


def check_conflict_markers(repo, path):
    """A problem for each line of `path` that is a merge's conflict marker."""
    return [f"{path.relative_to(repo)}:{number}: a merge's conflict marker: {line.strip()}"
            for number, line in enumerate(path.read_text().splitlines(), start=1)
            if CONFLICT_MARKER.match(line)]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    repo = pathlib.Path(sys.argv[1]).resolve()
    dcs = sys.argv[2]
    docs = [repo / "README.md", *sorted((repo / "docs").glob("*.md"))]
    links, commands = [], []
    problems = [p for path in docs for p in check_links(repo, path, links)]
    problems += [p for path in docs for p in check_commands(repo, dcs, path, commands)]
    problems += [p for path in docs for p in check_conflict_markers(repo, path)]
    for problem in problems:
        print(problem)
    print(f"check_docs: {len(problems)} problem(s) in {len(links)} links of "
          f"{', '.join(str(path.relative_to(repo)) for path in docs)} and {len(commands)} "
          f"`dcs` commands of their code blocks ({', '.join(sorted(set(commands)))})")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
