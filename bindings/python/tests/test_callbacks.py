"""Callbacks from the C library (a trace, play's and record's progress): what
they raise reaches the call that ran them, and nothing process-wide changes
(sys.unraisablehook stays as it is, whatever the threads do)."""
import sys
import threading

import pytest

import lsc


class Boom(Exception):
    pass


def test_four_threads_with_traces_leave_the_unraisable_hook_alone():
    hook = sys.unraisablehook
    calls = 3000
    errors = []
    seen = [0] * 4
    raised = [0] * 4

    def worker(k):
        try:
            with lsc.open("sim") as c:
                def trace(direction, frame):
                    seen[k] += 1
                    if fail[0]:
                        raise Boom("thread %d" % k)
                fail = [False]
                c.trace(trace)
                for i in range(calls):
                    fail[0] = i % 500 == 499
                    if fail[0]:
                        with pytest.raises(Boom, match="thread %d$" % k):
                            c.battery()
                        raised[k] += 1
                    else:
                        assert c.battery() == 7500
                    if sys.unraisablehook is not hook:
                        errors.append("thread %d: the hook changed at call %d" % (k, i))
                        return
        except BaseException as e:  # noqa: B902 (reported by the test)
            errors.append("thread %d: %r" % (k, e))

    threads = [threading.Thread(target=worker, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    assert sys.unraisablehook is hook
    assert raised == [calls // 500] * 4
    assert all(n >= 2 * calls for n in seen)  # each request's frame and its reply


def test_what_a_trace_raises_ends_the_call_in_the_main_thread(sim):
    hook = sys.unraisablehook

    def trace(direction, frame):
        raise Boom(direction)
    sim.trace(trace)
    with pytest.raises(Boom, match="^tx$"):
        sim.battery()
    sim.trace(None)
    assert sim.battery() == 7500
    assert sys.unraisablehook is hook


def test_what_progress_raises_ends_a_play_and_a_record(sim):
    hook = sys.unraisablehook
    a = lsc.Action([1], [(0, (1000,)), (100, (1100,))])

    def progress(step, elapsed):
        raise Boom("play")
    with pytest.raises(Boom, match="^play$"):
        sim.play(a, lead_ms=0, progress=progress)

    def taken(action, took):
        raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        sim.record([1], every_ms=10, count=3, unload=False, progress=taken)
    assert sim.battery() == 7500
    assert sys.unraisablehook is hook


def test_a_trace_exception_in_a_thread_is_that_threads(sim):
    # a call in another thread than the main one runs its callbacks itself
    got = []

    def run():
        try:
            sim.battery()
        except Boom as e:
            got.append(str(e))
    sim.trace(lambda d, f: (_ for _ in ()).throw(Boom("elsewhere")))
    t = threading.Thread(target=run)
    t.start()
    t.join()
    sim.trace(None)
    assert got == ["elsewhere"]
