#!/usr/bin/env python3
"""README.md is a test: every `$ ` command in its examples runs verbatim, in document order, from a
fresh folder laid out like a fresh clone (tests/, scripts/ and build/ as links), against a fresh
soiqd started the way `make run` starts it (scripts/run-server) and, from the PACS example on, the
demo PACS of scripts/demo-pacs with soiqd restarted on it, as the README says. Each command must
exit 0 and print what the README shows (stdout, then stderr), except:
  - timings ("3.6 s", "103.7 ms"), sizes ("2.9 MB", "57456 bytes") and DICOM UIDs made at run time;
  - the test's own ports, which stand for the README's 127.0.0.1:50051, 127.0.0.1:50080 and
    127.0.0.1:11112;
  - a line "..." in the README, which stands for any number of lines;
  - runs of spaces (table columns are as wide as their values).
A command's own 127.0.0.1:50080 (a DICOMweb URL given to curl) is the test's soiqd's HTTP port.
So an example that drifts from what soiq prints fails here, not in a reader's terminal. And every
picture the README shows (`![..](docs/pictures/NAME)`) must be one its commands just made, of the
same size as the committed one: a picture cannot drift from the command beside it either.

Usage: readme_test.py SOURCE_DIR BUILD_DIR
"""
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

SOURCE, BUILD = (os.path.abspath(p) for p in sys.argv[1:3])


def examples(text, fenced=True):
    """(command, expected output lines) for every `$ ` line of `text`: of its plain code blocks (a
    README), or of all of it (a transcript such as `make demo` prints)."""
    out, lines = [], text.split("\n")
    inside = plain = not fenced  # in a code block; in one without a language (an example)
    i = 0
    while i < len(lines):
        line = lines[i]
        i += 1
        if fenced and line.startswith("```"):
            inside, plain = not inside, not inside and line == "```"
            continue
        if not plain or not line.startswith("$ "):
            continue
        command = line[2:]
        while command.endswith("\\"):  # continuation lines
            command = command[:-1] + " " + lines[i].strip()
            i += 1
        expected = []
        while i < len(lines) and not lines[i].startswith("$ ") and not (fenced and lines[i].startswith("```")):
            expected.append(lines[i])
            i += 1
        while expected and not expected[-1].strip():
            expected.pop()
        out.append((command, expected))
    return out


RUN_TIME = [
    (re.compile(r"\b1\.2\.276\.0\.7230010\.[0-9.]+"), "<uid>"),  # DCMTK-made UIDs of exported SEGs
    (re.compile(r"\b[0-9]+(\.[0-9]+)? (ms|s)\b"), "<time>"),
    (re.compile(r"\b[0-9]+(\.[0-9]+)? (MB|kB|bytes)\b"), "<size>"),
]


def normalised(line, ports):
    for actual, shown in ports.items():
        line = line.replace(actual, shown)
    for pattern, token in RUN_TIME:
        line = pattern.sub(token, line)
    return " ".join(line.split())


def matches(expected, actual):
    """Whether `actual` lines fit `expected`, where a "..." line stands for any lines."""
    if not expected:
        return not actual
    if expected[0] == "...":
        return any(matches(expected[1:], actual[k:]) for k in range(len(actual) + 1))
    return bool(actual) and expected[0] == actual[0] and matches(expected[1:], actual[1:])


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for_port(port, process, what):
    for _ in range(300):
        if process.poll() is not None:
            raise SystemExit(f"FAIL: {what} exited at start with {process.returncode}")
        with socket.socket() as s:
            if s.connect_ex(("127.0.0.1", port)) == 0:
                return
        time.sleep(0.1)
    raise SystemExit(f"FAIL: {what} did not listen on {port}")


class Services:
    """soiqd as `make run` starts it, and the demo PACS when the README asks for it."""

    def __init__(self, root, env):
        self.root, self.env = root, env
        self.soiqd_port, self.http_port, self.pacs_port = free_port(), free_port(), free_port()
        self.soiqd = self.pacs = None

    def start_soiqd(self, pacs=None):
        self.stop(self.soiqd)
        env = dict(self.env, SOIQ_LISTEN=f"127.0.0.1:{self.soiqd_port}", SOIQ_HTTP=f"127.0.0.1:{self.http_port}",
                   SOIQ_DB="var/soiq.db")
        if pacs:
            env["SOIQ_PACS"] = pacs
        self.soiqd = subprocess.Popen(["scripts/run-server", "build"], cwd=self.root, env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                      start_new_session=True)
        wait_for_port(self.soiqd_port, self.soiqd, "soiqd")

    def start_pacs(self):
        self.pacs = subprocess.Popen(["scripts/demo-pacs", str(self.pacs_port)], cwd=self.root, env=self.env,
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                     start_new_session=True)
        for line in self.pacs.stdout:  # it says so once the sample is stored
            if line.startswith("demo PACS:"):
                break
        if self.pacs.poll() is not None:
            raise SystemExit("FAIL: scripts/demo-pacs did not start")
        self.start_soiqd(pacs=f"SOIQDEMO@127.0.0.1:{self.pacs_port}")

    @staticmethod
    def stop(process):
        if process and process.poll() is None:
            os.killpg(process.pid, signal.SIGTERM)
            process.wait(timeout=30)

    def close(self):
        self.stop(self.soiqd)
        self.stop(self.pacs)


def check_make_demo(root, env, readme):
    """`make demo` (scripts/demo) prints the README's offline commands and what the README shows."""
    r = subprocess.run(["scripts/demo", "build"], cwd=root, env=env, capture_output=True, text=True, timeout=600)
    shown = examples(r.stdout, fenced=False)
    failures = 0 if r.returncode == 0 and shown else 1
    for command, printed in shown:
        want = [normalised(l, {}) for l in readme.get(command, ["(not in README.md)"])]
        got = [normalised(l, {}) for l in printed]
        if "" in got:  # scripts/demo ends each command's output with a blank line
            got = got[:got.index("")]
        if not matches(want, got):
            failures += 1
            print(f"FAIL: make demo: $ {command}\n  README shows: {want}\n  make demo printed: {got}")
    print(("FAIL" if failures else "ok") + f": make demo ({len(shown)} commands, exit {r.returncode})")
    return failures


def png_size(path):
    """(width, height) from a PNG's IHDR, or None when the file is not a PNG."""
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


def check_pictures(root, text):
    """Each picture the README shows was made by its commands in `root`, the size of the committed one."""
    failures = 0
    for name in sorted(set(re.findall(r"\]\((docs/pictures/[^)\s]+)\)", text))):
        made, committed = os.path.join(root, name), os.path.join(SOURCE, name)
        if not os.path.exists(made):
            failures += 1
            print(f"FAIL: README shows {name}, but none of its commands made it")
        elif not os.path.exists(committed) or png_size(made) != png_size(committed):
            failures += 1
            print(f"FAIL: {name}: the commands made {png_size(made)}, the committed one is "
                  f"{png_size(committed) if os.path.exists(committed) else 'missing'}")
        else:
            print(f"ok: {name} {png_size(made)}")
    return failures


def main():
    root = tempfile.mkdtemp(prefix="soiq-readme-")
    for name, target in (("tests", os.path.join(SOURCE, "tests")), ("scripts", os.path.join(SOURCE, "scripts")),
                         ("build", BUILD)):
        os.symlink(target, os.path.join(root, name))
    env = {k: v for k, v in os.environ.items() if not k.startswith("SOIQ_")}
    services = Services(root, env)
    env["SOIQ_SERVER"] = f"127.0.0.1:{services.soiqd_port}"
    ports = {f"127.0.0.1:{services.soiqd_port}": "127.0.0.1:50051",
             f"127.0.0.1:{services.http_port}": "127.0.0.1:50080",
             f"127.0.0.1:{services.pacs_port}": "127.0.0.1:11112"}
    failures = 0
    readme_text = open(os.path.join(SOURCE, "README.md"), encoding="utf-8").read()
    readme = examples(readme_text)
    try:
        services.start_soiqd()
        for command, expected in readme:
            if command.startswith("build/client/soiq pacs") and services.pacs is None:
                services.start_pacs()
            # A URL of DICOMweb in a command (curl) names the README's port: the test's own is used.
            run = command.replace("127.0.0.1:50080", f"127.0.0.1:{services.http_port}")
            r = subprocess.run(run, shell=True, cwd=root, env=env, capture_output=True, text=True, timeout=600)
            actual = [normalised(l, ports) for l in (r.stdout + r.stderr).split("\n")]
            while actual and not actual[-1]:
                actual.pop()
            want = [normalised(l, ports) for l in expected]
            if r.returncode != 0 or not matches(want, actual):
                failures += 1
                print(f"FAIL: $ {command}\n  exit {r.returncode}\n  README shows:")
                print("\n".join("    " + l for l in want))
                print("  soiq printed:")
                print("\n".join("    " + l for l in actual))
            else:
                print(f"ok: $ {command}")
        failures += check_pictures(root, readme_text)
        failures += check_make_demo(root, env, dict(readme))
    finally:
        services.close()
        shutil.rmtree(root, ignore_errors=True)
    print(f"readme_test: {failures} failed" if failures else "readme_test: all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
