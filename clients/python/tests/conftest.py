"""A real soiqd for the Python client's tests: started on a free loopback port (--port-file) with its
own SQLite store, stopped at the end. Paths come from the environment ctest sets:
SOIQD and SOIQ (the binaries), SOIQ_TEST_DATA (tests/data)."""

import os
import subprocess
import tempfile
import time

import pytest


def _start(tmp, name, *args):
    port_file = os.path.join(tmp, name + ".port")
    log = open(os.path.join(tmp, name + ".log"), "w")
    proc = subprocess.Popen([os.environ["SOIQD"], "--listen", "127.0.0.1:0", "--port-file", port_file,
                             "--db", os.path.join(tmp, name + ".db"), "--workers", "2", *args],
                            stderr=log, stdout=log)
    for _ in range(400):
        if os.path.exists(port_file) and open(port_file).read().strip():
            return proc, "127.0.0.1:" + open(port_file).read().strip()
        if proc.poll() is not None:
            break
        time.sleep(0.025)
    proc.kill()
    raise RuntimeError("soiqd did not start: " + open(os.path.join(tmp, name + ".log")).read())


class Soiqd:
    def __init__(self, *args):
        self.dir = tempfile.TemporaryDirectory()
        self.proc, self.address = _start(self.dir.name, "soiqd", *args)

    def cli(self, *args, token_file=None):
        """`soiq` against this soiqd: its stdout (a failure fails the test with stderr)."""
        cmd = [os.environ["SOIQ"], "--server", self.address]
        if token_file:
            cmd += ["--token-file", token_file]
        done = subprocess.run(cmd + list(args), capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        return done.stdout

    def stop(self):
        self.proc.terminate()
        self.proc.wait(timeout=30)
        self.dir.cleanup()


@pytest.fixture(scope="module")
def demo_soiqd():
    """soiqd with `soiq demo-load`'s synthetic cohort, as the README's first session has it."""
    s = Soiqd()
    s.cli("demo-load")
    yield s
    s.stop()


@pytest.fixture
def soiqd():
    s = Soiqd()
    yield s
    s.stop()


@pytest.fixture
def data():
    return os.environ["SOIQ_TEST_DATA"]
