"""Controller.interrupt(): lsc_device_interrupt from Python."""
import threading
import time

import pytest

import lsc
from conftest import test_s


def test_interrupt_takes_the_next_wait(sim):
    sim.interrupt()
    sim.move({1: 1200}, time_ms=100)  # only sends: does not take it
    with pytest.raises(lsc.Interrupted, match="interrupted"):
        sim.battery()
    assert sim.battery() == 7500  # one interrupt, one call
    assert issubclass(lsc.Interrupted, lsc.Error)


def test_interrupt_from_another_thread_ends_a_wait(lsc_sim):
    s = lsc_sim()
    with lsc.open(s.path) as c:
        at = []

        def later():
            time.sleep(0.1)  # (if the wait has not begun, it takes it at once: the same)
            at.append(time.monotonic())
            c.interrupt()
        t = threading.Thread(target=later)
        t.start()
        with pytest.raises(lsc.Interrupted):
            c.wait_group(timeout=None)
        back = time.monotonic()
        t.join()
        assert back - at[0] < test_s(1.5)
        assert c.battery() > 0
    c.interrupt()  # closed: nothing
