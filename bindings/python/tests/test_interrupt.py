"""Controller.interrupt(): lsc_device_interrupt from Python."""
import threading
import time

import pytest

import lsc
from conftest import test_s, wait_until


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


# A play of six seconds: 0 ms to its first keyframe, then 3 s to each next one.
SIX_SECONDS = [(0, (1000,)), (3000, (1500,)), (3000, (2000,))]


def end_a_play_from_another_thread(c, how, play_in_main=True):
    """Plays SIX_SECONDS on c and, once its first frame went, calls how(c)
    in another thread; returns (the play's PlayResult or exception, the
    seconds from that call to the play's end)."""
    started = threading.Event()
    at = []

    def progress(step, elapsed):
        if step is not None:
            started.set()

    def play():
        try:
            return c.play(lsc.Action([1], SIX_SECONDS), lead_ms=0, progress=progress)
        except lsc.Error as e:
            return e

    def other():
        assert started.wait(test_s(30))
        at.append(time.monotonic())
        how(c)
    if play_in_main:
        t = threading.Thread(target=other)
        t.start()
        out = play()
    else:
        got = []
        t = threading.Thread(target=lambda: got.append(play()))
        t.start()
        other()
        while t.is_alive():
            t.join(0.01)
        out = got[0]
    end = time.monotonic()
    t.join()
    return out, end - at[0]


@pytest.mark.parametrize("play_in_main", [True, False])
@pytest.mark.parametrize("how", ["stop", "halt"])
def test_stop_or_halt_from_another_thread_ends_a_play(lsc_sim, how, play_in_main):
    s = lsc_sim()
    with lsc.open(s.path) as c:
        out, took = end_a_play_from_another_thread(c, lambda c: getattr(c, how)(),
                                                   play_in_main)
        assert isinstance(out, lsc.PlayResult), out
        assert out.stopped and out.keyframe < len(SIX_SECONDS), out  # (the last never went)
        assert took < test_s(1.5)
        assert c.battery() > 0  # nothing left over for the next call


def test_interrupt_from_another_thread_ends_a_play(lsc_sim):
    s = lsc_sim()
    with lsc.open(s.path) as c:
        out, took = end_a_play_from_another_thread(c, lambda c: c.interrupt())
        assert isinstance(out, lsc.Interrupted), out
        assert took < test_s(1.5)
        assert c.battery() > 0


def test_halt_from_another_thread_ends_a_moves_wait(lsc_sim):
    s = lsc_sim()
    with lsc.open(s.path) as c:
        at = []

        def later():
            wait_until(lambda: c._long, 30, "the move's wait")
            at.append(time.monotonic())
            c.halt()
        t = threading.Thread(target=later)
        t.start()
        with pytest.raises(lsc.Interrupted):
            c.move({1: 2000}, time_ms=6000, wait=True)
        back = time.monotonic()
        t.join()
        assert back - at[0] < test_s(1.5)


def test_another_threads_calls_get_in_during_a_wait_without_limit(lsc_sim, groups_file):
    s = lsc_sim("--fast", "--groups", groups_file)
    with lsc.open(s.path) as c:
        got = []
        t = threading.Thread(target=lambda: got.append(c.notification(timeout=None)))
        t.start()
        wait_until(lambda: c._long == "wait", 30, "the wait")
        for _ in range(20):  # each ends the wait for its turn; the wait goes on
            begun = time.monotonic()
            assert c.battery() > 0
            assert time.monotonic() - begun < test_s(1.5)
        assert t.is_alive() and not got
        c.run(1)
        t.join(test_s(30))
        assert got and got[0].kind == lsc.NotificationKind.RUN
