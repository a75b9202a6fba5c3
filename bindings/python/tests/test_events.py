"""A controller in a program's own event loop: Controller.fileno() with
selectors, next_event() and ready(); asyncio's anotifications() and
await_group(); against lsc-sim's pty, through lscd, and on "sim"."""
import asyncio
import os
import selectors
import subprocess
import time

import pytest

import lsc
from conftest import program, test_s, wait_until

RUN = lsc.Notification("action_group_run", 1, 1)
COMPLETE = lsc.Notification("action_group_complete", 1, 1)


def selector_loop(c, seconds):
    """Group 1's notifications, waiting in a selector on the descriptor and
    for next_event(), until its end or seconds."""
    got = []
    deadline = time.monotonic() + seconds
    with selectors.DefaultSelector() as sel:
        sel.register(c, selectors.EVENT_READ)
        while COMPLETE not in got and time.monotonic() < deadline:
            nxt = c.next_event()
            left = deadline - time.monotonic()
            sel.select(left if nxt is None else min(nxt, left))
            got += c.ready()
    return got


@pytest.fixture
def lscd(lsc_sim, groups_file, tmp_path):
    """lscd serving an lsc-sim, as its "lscd:PATH" name."""
    exe = program("LSCD", "lscd")
    if not exe:
        pytest.skip("lscd not found (set LSCD)")
    s = lsc_sim("--fast", "--groups", groups_file)
    sock = str(tmp_path / "arm.sock")
    p = subprocess.Popen([exe, "--port", s.path, "--socket", sock],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)

    def answers():
        try:
            lsc.open("lscd:" + sock).close()
            return True
        except lsc.Error:
            return False
    try:
        wait_until(answers, 30, "lscd answering on " + sock)
        yield "lscd:" + sock
    finally:
        p.terminate()
        p.wait(timeout=test_s(30))
        p.stderr.close()


def test_selectors_pty(lsc_sim, groups_file):
    s = lsc_sim("--fast", "--groups", groups_file)
    with lsc.open(s.path) as c:
        assert c.fileno() >= 0
        assert c.next_event() is None
        c.run(1)
        assert selector_loop(c, test_s(30)) == [RUN, COMPLETE]


def test_selectors_lscd(lscd):
    with lsc.open(lscd) as c:
        assert c.fileno() >= 0
        c.run(1)
        assert selector_loop(c, test_s(30)) == [RUN, COMPLETE]


def test_selectors_sim(sim):
    # "sim" follows the real clock and has a descriptor: a timer, readable
    # when it sends something of its own accord
    assert sim.fileno() >= 0
    assert sim.next_event() is None
    start = sim.now_ms()
    sim.run(1)
    assert sim.next_event() == 0
    assert selector_loop(sim, test_s(30)) == [RUN, COMPLETE]
    assert sim.next_event() is None
    # (group 1 takes time on its clock; the wall clock's passed with it)
    assert sim.now_ms() - start >= 100


async def notifications_until_end(c):
    got = []
    async for n in c.anotifications(timeout=test_s(30)):
        got.append(n)
        if n.kind != lsc.NotificationKind.RUN:
            break
    return got


@pytest.mark.parametrize("where", ["pty", "lscd", "sim"])
def test_asyncio(where, request, lsc_sim, groups_file):
    if where == "pty":
        name = lsc_sim("--fast", "--groups", groups_file).path
    elif where == "lscd":
        name = request.getfixturevalue("lscd")
    else:
        name = "sim"

    async def main(c):
        c.run(1)
        got = await notifications_until_end(c)
        c.run(1)
        end = await c.await_group(1, timeout=test_s(30))
        # other tasks ran while it waited
        ticks = 0

        async def tick():
            nonlocal ticks
            while True:
                ticks += 1
                await asyncio.sleep(0.001)
        t = asyncio.ensure_future(tick())
        c.run(1)
        await c.await_group(1, timeout=test_s(30))
        t.cancel()
        return got, end, ticks
    with lsc.open(name) as c:
        got, end, ticks = asyncio.run(main(c))
    assert got == [RUN, COMPLETE]
    assert end == COMPLETE
    assert ticks > 1


def test_asyncio_timeouts(lsc_sim, groups_file):
    s = lsc_sim("--fast", "--groups", groups_file)

    async def main(c):
        got = [n async for n in c.anotifications(timeout=0.05)]
        with pytest.raises(lsc.Timeout):
            await c.await_group(1, timeout=0.05)
        return got
    with lsc.open(s.path) as c:
        assert asyncio.run(main(c)) == []
    with lsc.open("sim") as c:  # nothing runs: at once
        assert asyncio.run(main(c)) == []


def test_a_coroutine_never_waits_for_another_threads_call(lsc_sim):
    # a play in another thread holds the controller: await_group waits for it
    # in an executor, while the loop goes on (ticks)
    import threading
    s = lsc_sim()
    with lsc.open(s.path) as c:
        started = threading.Event()

        def progress(step, elapsed):
            started.set()
            return not stop.is_set()
        stop = threading.Event()
        a = lsc.Action([1], [(0, (1000,)), (60000, (2000,))])
        t = threading.Thread(target=c.play, args=(a,), kwargs={"lead_ms": 0,
                                                                "progress": progress})
        t.start()
        assert started.wait(test_s(30))

        async def main():
            ticks = 0

            async def tick():
                nonlocal ticks
                while True:
                    ticks += 1
                    await asyncio.sleep(0.001)
            ticker = asyncio.ensure_future(tick())
            waiting = asyncio.ensure_future(c.await_group(timeout=test_s(30)))
            begun = time.monotonic()
            while ticks < 50:  # the loop runs while the play holds the controller
                await asyncio.sleep(0.001)
            assert time.monotonic() - begun < test_s(5)  # (not after the play's 60 s)
            assert not waiting.done() and c._long
            stop.set()
            waiting.cancel()
            ticker.cancel()
            return ticks
        try:
            assert asyncio.run(main()) >= 50
        finally:
            stop.set()
            t.join()
