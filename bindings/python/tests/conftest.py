"""Fixtures of the Python bindings' tests.

The library is $LSC_LIBRARY (a build tree's liblsc.so.2; ctest and
debian/rules set it), else the installed liblsc.so.2. The package is the one
on sys.path: PYTHONPATH=bindings/python for the source tree, the installed
python3-lsc otherwise. Programs the tests use, each from the environment or
else from PATH: LSC_SIM (lsc-sim, for the pseudo-terminal tests), LSC_LAYOUT
(the layout program; else it is compiled with cc against the installed
headers), LSC_HID_DOUBLE_LIB (the HID test double, preloaded into a child
Python). A test whose program is missing is skipped, saying which.

Waits that bound how long a test may take scale with LSC_TEST_TIME_SCALE (a
positive integer up to 1000, default 1), as tests/test_time.h does.
"""
import os
import select
import shutil
import signal
import subprocess
import sys
import time

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "data")

# The xArm's profile as shipped (examples/arms/xarm.conf's joints, limits and
# geometry), for tests that need the whole chain (the tests run outside the
# tree too: tests/data has no copy of the shipped one).
XARM_PROFILE = """
gripper 1 bus limits=0..700
wrist-rotate 2 bus limits=-115deg..115deg
wrist 3 bus limits=-115deg..115deg
elbow 4 bus limits=-115deg..115deg
shoulder 5 bus limits=-115deg..115deg
base 6 bus limits=-115deg..115deg
chain: base shoulder elbow wrist wrist-rotate gripper
links: height=64.7mm upper=98.8mm fore=94.7mm tool=158.8mm
"""


def pytest_report_header(config):
    try:
        import lsc
        where = "lsc %s from %s, over %s" % (lsc.__version__, os.path.dirname(lsc.__file__),
                                             lsc.library_path)
    except ImportError as e:
        where = "lsc cannot be imported: %s" % e
    return [where,
            "lsc-sim: %s" % (program("LSC_SIM", "lsc-sim") or "none (pty tests skipped)")]


def time_scale():
    """LSC_TEST_TIME_SCALE: a positive integer up to 1000, else 1."""
    s = os.environ.get("LSC_TEST_TIME_SCALE", "")
    return int(s) if s.isdigit() and 1 <= int(s) <= 1000 else 1


def test_s(seconds):
    """A wall-clock bound of a test, scaled for a slow or busy machine."""
    return seconds * time_scale()


test_s.__test__ = False  # not a test (pytest collects test_* names)


def program(var, name):
    """The program $var, else name on PATH, else None."""
    p = os.environ.get(var, "")
    if p:
        return p
    return shutil.which(name)


def wait_until(cond, seconds, what):
    """Polls cond (cheap, no side effects) until true; fails after seconds (scaled)."""
    end = time.monotonic() + test_s(seconds)
    while not cond():
        if time.monotonic() > end:
            raise AssertionError("%s did not happen within %d s" % (what, test_s(seconds)))
        time.sleep(0.005)


class LscSim:
    """An lsc-sim process serving a virtual controller on a pseudo-terminal."""

    def __init__(self, exe, *args):
        self.proc = subprocess.Popen([exe, *args], stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE)
        ready, _, _ = select.select([self.proc.stdout], [], [], test_s(30))
        if not ready:
            self.proc.kill()
            raise AssertionError("lsc-sim printed no path within %d s" % test_s(30))
        self.path = self.proc.stdout.readline().decode().strip()
        if not self.path:
            self.proc.wait()
            raise AssertionError("lsc-sim failed: %s" % self.proc.stderr.read().decode())

    def button(self):
        """SIGUSR1: lsc-sim runs its --button group."""
        self.proc.send_signal(signal.SIGUSR1)

    def stop(self):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(timeout=test_s(30))
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.proc.stdout.close()
        self.proc.stderr.close()


@pytest.fixture
def lsc_sim():
    """A function starting lsc-sim with the given options (stopped at the end)."""
    exe = program("LSC_SIM", "lsc-sim")
    if not exe:
        pytest.skip("lsc-sim not found (set LSC_SIM, or install the lscctl package)")
    sims = []

    def start(*args):
        s = LscSim(exe, *args)
        sims.append(s)
        return s
    yield start
    for s in sims:
        s.stop()


@pytest.fixture
def groups_file():
    return os.path.join(DATA, "groups.txt")


@pytest.fixture
def sim():
    """The built-in virtual controller."""
    import lsc
    c = lsc.open("sim")
    yield c
    c.close()


def child_env(**extra):
    """The environment for a child Python: this one's, with the package on
    sys.path as it is here."""
    import lsc
    env = dict(os.environ)
    pkg = os.path.dirname(os.path.dirname(os.path.abspath(lsc.__file__)))
    env["PYTHONPATH"] = pkg + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    env.update(extra)
    return env


def run_python(code_or_args, env=None, timeout=60, **kw):
    """Runs a child Python (this interpreter) to its end; returns the CompletedProcess."""
    args = ["-c", code_or_args] if isinstance(code_or_args, str) else list(code_or_args)
    return subprocess.run([sys.executable, *args], env=env or child_env(), capture_output=True,
                          text=True, timeout=test_s(timeout), **kw)
