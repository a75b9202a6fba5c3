"""A port opened twice: by this program (an earlier lsc.open() not closed)
the message says so; by another program it says that. The library tells
them apart when the lock is refused (Linux: which of this process's
descriptors holds it), so lscctl and every front end say the same."""
import subprocess
import sys

import pytest

import lsc

from conftest import child_env, test_s


def test_second_open_in_this_program(lsc_sim):
    s = lsc_sim("--fast")
    with lsc.open(s.path) as first:
        with pytest.raises(lsc.Busy) as e:
            lsc.open(s.path)
        assert s.path in str(e.value)
        assert "this program has it open already" in str(e.value)
        assert "another program" not in str(e.value)
        assert first.battery() == 7500  # the first is untouched
    with lsc.open(s.path) as again:  # closed: it opens
        assert again.battery() == 7500


def test_open_while_another_program_has_it(lsc_sim):
    s = lsc_sim("--fast")
    holder = subprocess.Popen(
        [sys.executable, "-c",
         "import sys, lsc\nc = lsc.open(sys.argv[1])\nprint('open', flush=True)\n"
         "sys.stdin.read()\n", s.path],
        env=child_env(), stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "open"
        with pytest.raises(lsc.Busy) as e:
            lsc.open(s.path)
        assert "another program has it open" in str(e.value)
        assert "this program" not in str(e.value)
    finally:
        holder.stdin.close()
        holder.wait(timeout=test_s(30))
        holder.stdout.close()
