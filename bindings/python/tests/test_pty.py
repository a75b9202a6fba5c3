"""The public calls against lsc-sim on a pseudo-terminal: a real serial link
(termios), real time, another process answering; and what only a real link
shows: Busy, Timeout, a device that goes away, Ctrl-C in a wait without limit
or in a play, threads taking turns."""
import os
import signal
import subprocess
import sys
import threading

import pytest

import lsc
from conftest import child_env, program, test_s, wait_until


def test_every_request(lsc_sim, groups_file):
    s = lsc_sim("--fast", "--groups", groups_file, "--battery", "7400")
    with lsc.open(s.path) as c:
        assert c.kind == "serial"
        assert c.name == s.path
        assert c.battery() == 7400
        assert c.read([1, 2, 3]) == {1: 1500, 2: 1500, 3: 1500}
        c.move({1: 1000, 2: 1200}, time_ms=100, wait=True, tolerance=0)  # (10: it may end 1 short)
        assert c.read([1, 2]) == {1: 1000, 2: 1200}
        assert c.offsets([1]) == {1: 0}
        c.adjust_offset(1, 3)
        assert c.offsets([1]) == {1: 3}
        c.unload([1, 2])
        c.speed(1, 100)
        assert c.request(15) == (7400).to_bytes(2, "little")
        c.send(7)
        assert c.groups() == []  # a real controller does not say


def test_run_wait_and_notifications(lsc_sim, groups_file):
    s = lsc_sim("--fast", "--groups", groups_file)
    with lsc.open(s.path) as c:
        end = c.run(1, times=2, wait=True, timeout=test_s(30))
        assert end == lsc.Notification("action_group_complete", 1, 2)
        c.run(1)
        got = []
        for n in c.notifications(timeout=test_s(30)):
            got.append(n)
            if n.kind == lsc.NotificationKind.COMPLETE:
                break
        assert got == [lsc.Notification("action_group_run", 1, 1),
                       lsc.Notification("action_group_complete", 1, 1)]
        with pytest.raises(lsc.Timeout):
            c.notification(timeout=0.05)


def test_button_notifications(lsc_sim, groups_file):
    s = lsc_sim("--fast", "--groups", groups_file, "--button", "1")
    with lsc.open(s.path) as c:
        s.button()
        kinds = []
        for n in c.notifications(timeout=test_s(30)):
            kinds.append((n.kind, n.group))
            if n.kind != lsc.NotificationKind.RUN:
                break
        assert kinds == [("action_group_run", 1), ("action_group_complete", 1)]


def test_stop_from_another_thread(lsc_sim, groups_file):
    s = lsc_sim("--fast", "--groups", groups_file)
    with lsc.open(s.path) as c:
        c.run(3)  # a minute long
        result = []
        t = threading.Thread(target=lambda: result.append(c.wait_group(3, timeout=test_s(60))))
        t.start()
        c.stop()  # gets in between the other thread's steps of waiting
        t.join(test_s(60))
        assert not t.is_alive()
        assert result == [lsc.Notification("action_group_stop", 0, 0)]


def test_busy(lsc_sim):
    s = lsc_sim("--fast")
    with lsc.open(s.path):
        with pytest.raises(lsc.Busy) as e:
            lsc.open(s.path)
        assert s.path in str(e.value) and e.value.code == -9


def test_fork_child_close_keeps_the_port(lsc_sim):
    """A child that inherited an open controller (fork) and closes it leaves the
    parent's claim alone: the port stays busy for every other program."""
    s = lsc_sim("--fast")
    with lsc.open(s.path) as c:
        pid = os.fork()
        if pid == 0:  # the child: closes its copy (as its garbage collector would)
            try:
                c.close()
            finally:
                os._exit(0)
        _, status = os.waitpid(pid, 0)
        assert os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0
        with pytest.raises(lsc.Busy):
            lsc.open(s.path)
        lscctl = program("LSCCTL", "lscctl")
        if lscctl:
            r = subprocess.run([lscctl, "--port", s.path, "battery"], capture_output=True,
                               timeout=test_s(60))
            assert r.returncode == 4, r.stderr
        assert c.battery() == 7500  # the parent still has it


def test_timeout(lsc_sim):
    s = lsc_sim("--fast", "--drop-replies", "1")
    with lsc.open(s.path, timeout_ms=200) as c:
        with pytest.raises(lsc.Timeout) as e:
            c.battery()
        assert isinstance(e.value, TimeoutError)
        assert "\n" not in str(e.value) and str(e.value)
        c.timeout_ms = test_s(1) * 1000  # 200 ms was for the wait above; a loaded machine needs more
        assert c.battery() == 7500  # the next is answered


def test_device_gone(lsc_sim):
    s = lsc_sim("--fast")
    c = lsc.open(s.path, timeout_ms=200)
    s.stop()
    with pytest.raises(lsc.Error) as e:
        for _ in range(3):
            c.battery()
    assert type(e.value) in (lsc.LinkError, lsc.NotFound, lsc.Timeout)
    c.close()


def test_play_keeps_its_schedule(lsc_sim):
    s = lsc_sim()  # paced at 9600 baud like a board
    a = lsc.Action([1, 2], [(0, (1000, 2000)), (100, (1100, 1900)), (100, (1200, 1800)),
                            (100, (1300, 1700))])
    with lsc.open(s.path) as c:
        steps = []
        r = c.play(a, lead_ms=100, progress=lambda step, ms: steps.append(step) or True)
        assert (r.frames, r.dropped, r.stopped) == (4, 0, False)
        assert r.total_ms == 400
        assert [st.keyframe for st in steps if st is not None] == [0, 1, 2, 3]
        # play ends on this clock; lsc-sim started the last move when its frame
        # arrived, behind by as long as the machine keeps it waiting: its end
        # is waited for
        wait_until(lambda: c.read([1, 2]) == {1: 1300, 2: 1700}, 30, "the last move's end")


def test_record(lsc_sim):
    s = lsc_sim("--fast")
    with lsc.open(s.path) as c:
        c.move({4: 1234}, time_ms=0, wait=True)
        a = c.record([4], every_ms=50, count=3)
        assert [k.positions for k in a] == [(1234,)] * 3


# The child gets Python's own Ctrl-C handling whatever it inherited: a shell
# that starts a command in the background without job control (`ctest ... &`
# in a script) ignores SIGINT for it, and Python then raises no
# KeyboardInterrupt (the wait would never end).
CTRL_C_CHILD = r"""
import signal, sys, lsc
signal.signal(signal.SIGINT, signal.default_int_handler)
c = lsc.open(sys.argv[1])
%s
print("waiting", flush=True)
try:
    %s
except KeyboardInterrupt:
    print("interrupted", flush=True)
    c.battery()  # the link is still good: nothing half-sent
    print("after", flush=True)
"""


def main_thread_sleeps(pid):
    """The child's main thread is asleep (in the C library's wait)."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "S"
    except OSError:
        return False


def interrupt_child(path, setup, call):
    """Runs call in a child Python on path, sends SIGINT once it waits in it,
    and returns the child's output."""
    p = subprocess.Popen([sys.executable, "-c", CTRL_C_CHILD % (setup, call), path],
                         env=child_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
    try:
        assert p.stdout.readline() == "waiting\n", p.stderr.read()
        wait_until(lambda: main_thread_sleeps(p.pid), 30, "the child's wait")
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=test_s(30))
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    assert p.returncode == 0, err
    return out


def test_ctrl_c_ends_a_wait_without_limit(lsc_sim):
    s = lsc_sim("--fast")
    out = interrupt_child(s.path, "", "c.notification(timeout=None)")
    assert out == "interrupted\nafter\n"


def test_ctrl_c_ends_a_group_wait(lsc_sim, groups_file):
    s = lsc_sim("--fast", "--groups", groups_file)
    out = interrupt_child(s.path, "", "c.run(3, wait=True)")
    assert out == "interrupted\nafter\n"


def test_ctrl_c_stops_a_play(lsc_sim):
    s = lsc_sim()
    setup = "a = lsc.Action([1], [(0, (1000,))] + [(60000, (1000 + k,)) for k in range(1, 5)])"
    out = interrupt_child(s.path, setup, "c.play(a, lead_ms=0)")
    assert out == "interrupted\nafter\n"


def test_ctrl_c_in_a_move_wait(lsc_sim):
    s = lsc_sim("--fast")
    out = interrupt_child(s.path, "", "c.move({1: 2000}, time_ms=60000, wait=True)")
    assert out == "interrupted\nafter\n"


def test_ctrl_c_stops_a_record(lsc_sim):
    s = lsc_sim("--fast")
    out = interrupt_child(s.path, "", "c.record([1], every_ms=60000, count=5)")
    assert out == "interrupted\nafter\n"
