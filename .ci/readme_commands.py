#!/usr/bin/env python3
"""Runs every command of README.md as written, in README order, from the repository root.

Every line of every ```sh block is run by bash (a line ending in a backslash continues on
the next); every ```python block is run by python3 as one program. `subsurf` is the binary
the Quick start builds (target/release, put first on PATH, as `cargo install` would). Files
the commands write into the repository are removed afterwards. Exit status 1, naming the
line, at the first command that fails.

    python3 .ci/readme_commands.py [--list] [--only PATTERN]
"""
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def blocks(text):
    """(kind, first line number, code) of every fenced sh / python block."""
    out = []
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        m = re.match(r"^```(sh|bash|python)\s*$", lines[i])
        if m:
            start = i + 1
            j = start
            while not lines[j].startswith("```"):
                j += 1
            out.append((m.group(1), start + 1, lines[start:j]))
            i = j
        i += 1
    return out


def commands(text):
    """(line number, kind, command) in README order."""
    out = []
    for kind, first, code in blocks(text):
        if kind == "python":
            out.append((first, "python", "\n".join(code)))
            continue
        pending, at = "", None
        for k, line in enumerate(code):
            stripped = line.strip()
            if not pending and (not stripped or stripped.startswith("#")):
                continue
            if at is None:
                at = first + k
            if stripped.endswith("\\"):
                pending += stripped[:-1] + " "
                continue
            out.append((at, "sh", pending + stripped))
            pending, at = "", None
    return out


def untracked():
    r = subprocess.run(
        ["git", "status", "--porcelain", "--untracked-files=all"],
        cwd=ROOT, capture_output=True, text=True, check=True,
    )
    return {l[3:] for l in r.stdout.splitlines() if l.startswith("?? ")}


def main():
    text = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read()
    cmds = commands(text)
    if "--list" in sys.argv:
        for line, kind, cmd in cmds:
            print(f"README.md:{line} [{kind}] {cmd}")
        return 0
    only = sys.argv[sys.argv.index("--only") + 1] if "--only" in sys.argv else None
    env = dict(os.environ)
    env["PATH"] = os.path.join(ROOT, "target", "release") + os.pathsep + env["PATH"]
    before = untracked()
    failed, ran = None, 0
    try:
        for line, kind, cmd in cmds:
            if only and not re.search(only, cmd):
                continue
            shown = cmd if kind == "sh" else f"python block ({len(cmd.splitlines())} lines)"
            print(f"==> README.md:{line}: {shown}", flush=True)
            t = time.time()
            if kind == "sh":
                r = subprocess.run(["bash", "-eo", "pipefail", "-c", cmd], cwd=ROOT, env=env)
            else:
                r = subprocess.run([sys.executable, "-c", cmd], cwd=ROOT, env=env)
            ran += 1
            print(f"    exit {r.returncode} in {time.time() - t:.1f} s", flush=True)
            if r.returncode != 0:
                failed = (line, shown, r.returncode)
                break
    finally:
        for path in sorted(untracked() - before):
            os.remove(os.path.join(ROOT, path))
    if failed:
        print(f"README.md:{failed[0]}: `{failed[1]}` failed with exit status {failed[2]}",
              file=sys.stderr)
        return 1
    print(f"{ran} of the README's {len(cmds)} commands ran as written")
    return 0


if __name__ == "__main__":
    sys.exit(main())
