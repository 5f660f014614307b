#!/usr/bin/env python3
"""Every option a command's help lists is accepted by that command's parser, in every spelling.

The help comes from the command table (`soiq help CMD`); this runs the real `soiq` with each
listed option (and a plausible value) and fails if the parser calls it unknown or unexpected. The
commands then stop for other reasons (a missing operand, no soiqd at the address given), which is
fine: only the parser's verdict on the option is checked. With the table's own agreement test
(tests/client/command_table_test.cpp, which reads the parsers' sources), help and parser cannot
disagree in either direction.

Usage: options_accepted_test.py SOIQ
"""
import concurrent.futures
import os
import re
import subprocess
import sys
import tempfile

SOIQ = sys.argv[1]
# Nothing listens there: a remote command that gets past its parser fails fast as unavailable.
NOWHERE = ["--server", "127.0.0.1:9", "--timeout", "0.5"]


def run(args, cwd):
    return subprocess.run([SOIQ] + args, cwd=cwd, capture_output=True, text=True, timeout=60)


def commands():
    """The command names of the overview: "soiq NAME ..." lines, pacs's verbs from its help."""
    overview = run(["help"], None).stdout
    names = []
    for m in re.finditer(r"^  soiq ([a-z][a-z-]*)", overview, re.M):
        if m.group(1) not in names and m.group(1) != "pacs":
            names.append(m.group(1))
    for verb in ("echo", "find", "pull", "push"):
        names.append("pacs " + verb)
    return names


def options(command):
    """(spellings, value placeholder) of each option line of `soiq help COMMAND`."""
    text = run(["help"] + command.split(), None).stdout
    block = text.split("\nOptions:\n", 1)[1].split("\n\n", 1)[0]
    found = []
    for line in block.splitlines():
        m = re.match(r"^  (-[-\w]+)(?:, (--[-\w]+))?(?: (\S+))?", line)
        if not m:
            continue
        spellings = [s for s in (m.group(1), m.group(2)) if s]
        if "--help" in spellings:
            continue
        found.append((spellings, m.group(3) or ""))
    return found


def value_for(placeholder):
    """A value of the placeholder's kind, so a parser that checks values does not stop first."""
    if not placeholder:
        return []
    first = placeholder.strip("'").split("|")[0]
    if first in ("N", "Y", "S", "SECONDS", "R") or first.startswith("S|") or placeholder.startswith("S|"):
        return ["1"]
    if first in ("D", "YYYYMMDD", "D|D1-D2"):
        return ["20200101"]
    if placeholder.startswith("'FEATURE"):
        return ["voxel_count > 0"]
    if first.startswith("OUT"):
        return ["out.nii.gz"]
    return [first if re.fullmatch(r"[a-z]+|[A-Z]", first) else "x"]


def main():
    failures = []
    runs = []  # (command line after NOWHERE, spelling)
    for command in commands():
        listed = options(command)
        if not listed and command not in ("health", "pacs echo", "completion", "man", "rm", "help"):
            failures.append(f"'soiq help {command}' lists no options")
        for spellings, placeholder in listed:
            for spelling in spellings:
                runs.append((command.split() + [spelling] + value_for(placeholder), spelling))
    # Most runs wait out their --timeout for the absent soiqd: several at a time, the test takes
    # seconds instead of a minute of a ctest slot spent waiting.
    with tempfile.TemporaryDirectory() as cwd, concurrent.futures.ThreadPoolExecutor(
            max_workers=2 * (os.cpu_count() or 1)) as pool:
        results = pool.map(lambda run_args: run(NOWHERE + run_args[0], cwd), runs)
        for (args, spelling), r in zip(runs, results):
            refused = re.search(r"unknown option '%s'|unexpected argument '%s'" % (
                re.escape(spelling), re.escape(spelling)), r.stderr)
            if refused:
                failures.append(f"soiq {' '.join(args)}: {r.stderr.strip()}")
    for f in failures:
        print("FAIL:", f)
    checked = len(runs)
    print(f"options_accepted_test: {checked} option spellings checked, {len(failures)} refused")
    sys.exit(1 if failures or checked < 50 else 0)


if __name__ == "__main__":
    main()
