"""Every public call against the built-in virtual controller ("sim": virtual
time, so waits take none)."""
import os

import pytest

import lsc
from conftest import DATA, test_s, wait_until

XARM = os.path.join(DATA, "xarm.conf")


def frames_sent(c):
    """A list that c's trace fills with the frames c sends (as bytes)."""
    sent = []
    c.trace(lambda d, f: sent.append(f) if d == "tx" else None)
    return sent


def test_open_and_close():
    c = lsc.open("sim")
    assert c.name == "sim"
    assert c.kind == "sim"
    assert not c.closed
    assert "sim" in repr(c)
    c.close()
    assert c.closed
    c.close()  # again is fine
    assert repr(c) == "<lsc.Controller closed>"
    with pytest.raises(lsc.Error, match="closed"):
        c.battery()


def test_context_manager():
    with lsc.open("sim") as c:
        assert c.battery() == 7500
    assert c.closed


def test_battery(sim):
    assert sim.battery() == 7500


def test_read_defaults(sim):
    assert sim.read([1, 2, 3]) == {1: 1500, 2: 1500, 3: 1500}
    assert sim.read(7) == {7: 1500}  # one servo


def test_move_then_read(sim):
    sent = frames_sent(sim)
    sim.move({1: 1500, 2: 1200}, time_ms=500, wait=True)
    # the move's frame exactly (docs/protocol.md), then the settle's reads
    assert sent[0] == bytes([0x55, 0x55, 0x0B, 0x03, 0x02, 0xF4, 0x01, 1, 0xDC, 0x05,
                             2, 0xB0, 0x04])
    assert sim.read([1, 2]) == {1: 1500, 2: 1200}


def test_move_without_wait_is_on_its_way(sim):
    t0 = sim.now_ms()
    sim.move({3: 2000}, time_ms=1000)
    assert sim.now_ms() - t0 < 1000
    pos = sim.read([3])[3]
    assert 1500 <= pos <= 2000
    sim.move({3: 2000}, time_ms=0, wait=True)
    assert sim.read([3]) == {3: 2000}


def test_move_wait_takes_the_move_time(sim):
    t0 = sim.now_ms()
    sim.move({4: 900}, time_ms=800, wait=True, tolerance=0)
    assert sim.now_ms() - t0 >= 800
    assert sim.read(4) == {4: 900}


def test_run_wait_returns_the_end(sim):
    n = sim.run(1, times=1, wait=True)
    assert n == lsc.Notification(lsc.NotificationKind.COMPLETE, 1, 1)
    assert n.kind == "action_group_complete"
    assert n.cmd == 8


def test_run_then_notifications(sim):
    assert sim.run(2, times=2) is None
    got = list(sim.notifications(timeout=60))
    assert got == [lsc.Notification("action_group_run", 2, 2),
                   lsc.Notification("action_group_complete", 2, 2)]


def test_wait_group_any(sim):
    sim.run(8)
    n = sim.wait_group(timeout=60)
    assert (n.kind, n.group) == (lsc.NotificationKind.COMPLETE, 8)


def test_notification_timeout_when_nothing_runs(sim):
    with pytest.raises(lsc.Timeout, match="nothing runs"):
        sim.notification(timeout=1)
    with pytest.raises(lsc.Timeout):
        sim.notification()  # no limit: on sim nothing can come, at once
    assert list(sim.notifications(timeout=0)) == []


def test_run_a_group_sim_lacks(sim):
    assert sim.groups() == [1, 2, 8]
    with pytest.raises(lsc.Timeout, match="no group 5"):
        sim.run(5, wait=True)


def test_run_forever_then_wait_without_limit(sim):
    with pytest.raises(lsc.Timeout):
        sim.run(1, times=0, wait=True)
    sim.stop()


def test_stop(sim):
    sim.run(2, times=0)
    assert sim.notification(timeout=1).kind == lsc.NotificationKind.RUN
    sim.stop()
    assert sim.notification(timeout=1) == lsc.Notification(lsc.NotificationKind.STOP, 0, 0)


def test_speed(sim):
    t0 = sim.now_ms()
    sim.run(1, wait=True)
    normal = sim.now_ms() - t0
    sim.speed(1, 200)
    t0 = sim.now_ms()
    sim.run(1, wait=True)
    fast = sim.now_ms() - t0
    assert fast < normal * 0.75, (normal, fast)
    sent = frames_sent(sim)
    sim.speed(None, 50)
    sim.speed(lsc.ALL_GROUPS, 300)
    assert sent == [bytes([0x55, 0x55, 0x05, 0x0B, 0xFF, 50, 0]),
                    bytes([0x55, 0x55, 0x05, 0x0B, 0xFF, 0x2C, 0x01])]


def test_unload(sim):
    sent = frames_sent(sim)
    sim.unload([1, 2, 3])
    sim.unload(4)
    assert sent == [bytes([0x55, 0x55, 0x06, 0x14, 0x03, 1, 2, 3]),
                    bytes([0x55, 0x55, 0x04, 0x14, 0x01, 4])]


def test_offsets(sim):
    assert sim.offsets([1, 2]) == {1: 0, 2: 0}
    sim.adjust_offset(2, -5)
    assert sim.offsets([2, 1]) == {2: -5, 1: 0}


def test_raw_send_and_request(sim):
    assert sim.request(15, b"") == bytes([0x4C, 0x1D])
    assert sim.request(21, bytes([1, 9]), reply_cmd=21) == bytes([1, 9, 0xDC, 0x05])
    sent = frames_sent(sim)
    sim.send(7)
    assert sent == [bytes([0x55, 0x55, 0x02, 0x07])]
    with pytest.raises(lsc.InvalidArgument):
        sim.send(8, bytes([1, 1, 0]))  # erases the groups on an xArm
    assert len(sent) == 1


def test_poll_and_dropped(sim):
    assert sim.poll(0) == 0
    sim.run(1)
    came = []  # (sim follows the real clock: its start comes within a second)
    wait_until(lambda: came.append(sim.poll(0.05)) or sum(came) >= 1, 30, "group 1's start")
    assert sim.dropped_notifications == 0


def test_timeout_ms(sim):
    assert sim.timeout_ms == 1000
    sim.timeout_ms = 250
    assert sim.timeout_ms == 250
    with pytest.raises(lsc.InvalidArgument):
        sim.timeout_ms = 0
    c = lsc.open("sim", timeout_ms=1234)
    assert c.timeout_ms == 1234
    c.close()


def test_trace_both_ways(sim):
    seen = []
    sim.trace(lambda d, f: seen.append((d, f)))
    sim.battery()
    assert seen == [("tx", bytes([0x55, 0x55, 0x02, 0x0F])),
                    ("rx", bytes([0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D]))]
    sim.trace(None)
    sim.battery()
    assert len(seen) == 2


def test_trace_exception_ends_the_call(sim):
    def boom(d, f):
        raise RuntimeError("from the trace")
    sim.trace(boom)
    with pytest.raises(RuntimeError, match="from the trace"):
        sim.battery()
    sim.trace(None)
    assert sim.battery() == 7500


def test_trace_refuses_what_it_cannot_call(sim):
    with pytest.raises(TypeError, match="trace"):
        sim.trace(5)
    assert sim.battery() == 7500  # nothing changed: later calls work


def test_play(sim):
    a = lsc.Action([1, 2], [(0, (1000, 2000)), (500, (1200, 1800)), (500, (1300, 1700))])
    r = sim.play(a, lead_ms=300)
    assert isinstance(r, lsc.PlayResult)
    assert (r.frames, r.dropped, r.keyframe, r.stopped) == (3, 0, 3, False)
    assert r.total_ms == 1300
    # (the real clock: the last move ends as late as the machine let it start)
    wait_until(lambda: sim.read([1, 2]) == {1: 1300, 2: 1700}, 30, "the last move's end")


def test_play_progress_and_stop(sim):
    a = lsc.Action([5], [(0, (1000,)), (400, (1100,)), (400, (1200,)), (400, (1300,))])
    steps = []

    def progress(step, elapsed):
        if step is not None:
            steps.append(step)
            return len(steps) < 2
        return True
    r = sim.play(a, lead_ms=200, speed=100, times=1, progress=progress)
    assert r.stopped
    assert r.frames == 2
    assert steps[0].lead_in and steps[0].servos == {5: 1000} and steps[0].time_ms == 200
    assert steps[1].keyframe == 1 and steps[1].servos == {5: 1100}


def test_play_progress_exception(sim):
    a = lsc.Action([5], [(0, (1000,)), (400, (1100,))])

    def progress(step, elapsed):
        raise ValueError("from progress")
    with pytest.raises(ValueError, match="from progress"):
        sim.play(a, progress=progress)
    assert sim.battery() == 7500  # usable after


def test_play_speed_and_times(sim):
    a = lsc.Action([1], [(200, (1000,)), (1000, (2000,))])
    r = sim.play(a, lead_ms=0, speed=200, times=3)
    assert r.frames == 6
    # the lead-in (0 ms) replaces the first keyframe 0; then 500, (100 + 500) x 2
    assert r.total_ms == 500 + 2 * 600


def test_record(sim):
    sim.move({1: 1100, 2: 1900}, time_ms=0)
    seen = []
    a = sim.record([1, 2], every_ms=100, count=3,
                   progress=lambda action, taken: seen.append(taken))
    assert a.ids == (1, 2)
    assert len(a) == 3
    assert [k.positions for k in a] == [(1100, 1900)] * 3
    # (on the real clock: each about the 100 ms asked, on a schedule from one start)
    assert all(abs(k.time_ms - 100) <= test_s(100) for k in a), [k.time_ms for k in a]
    assert seen.count(True) == 3


def test_ports():
    ports = lsc.ports()
    assert isinstance(ports, list)
    for p in ports:
        assert isinstance(p, lsc.Port)
        assert p.kind in ("serial", "hid")
        assert p.name


def test_arm_moves_by_joint_and_degrees():
    arm = lsc.Arm(XARM)
    with lsc.open("sim", arm=arm) as c:
        assert c.arm is arm
        sent = frames_sent(c)
        c.move({"base": "30deg", "gripper": 700}, time_ms=500, wait=True)
        # 30 degrees of a bus servo (0.24 degree a unit) from the middle: 625
        assert sent[0] == bytes([0x55, 0x55, 0x0B, 0x03, 0x02, 0xF4, 0x01,
                                 6, 0x71, 0x02, 1, 0xBC, 0x02])
        assert c.read(["base", "gripper"]) == {"base": 625, "gripper": 700}
        assert c.read(["base", 1], degrees=True) == {"base": 30.0, 1: 48.0}
        with pytest.raises(lsc.InvalidArgument, match="servo 6 appears twice"):
            c.read(["base", 6])
        c.move({"wrist": "-15.5deg"}, time_ms=0, wait=True)
        assert c.read(["wrist"], degrees=True) == {"wrist": -15.6}  # the nearest position's
        c.unload(["gripper", "base"])
        assert sent[-1] == bytes([0x55, 0x55, 0x05, 0x14, 0x02, 1, 6])


def test_arm_by_path_and_limits():
    with lsc.open("sim", arm=XARM) as c:
        sent = frames_sent(c)
        with pytest.raises(lsc.InvalidArgument, match="gripper") as e:
            c.move({"gripper": 800, "base": 500}, time_ms=100)
        assert e.value.code == -1
        with pytest.raises(lsc.InvalidArgument, match="wrist"):
            c.move({"wrist": "100deg"}, time_ms=100)
        with pytest.raises(lsc.InvalidArgument, match="elbow"):
            c.move({"elbow": 500}, time_ms=100)
        a = lsc.Action([1, 6], [(0, (500, 500)), (100, (900, 500))])
        with pytest.raises(lsc.InvalidArgument, match="keyframe 2"):
            c.play(a)
        assert sent == []
        c.arm = None
        c.move({1: 800}, time_ms=0)
        assert len(sent) == 1


def test_degrees_needs_an_arm(sim):
    with pytest.raises(lsc.InvalidArgument, match="arm profile"):
        sim.read([1], degrees=True)
    with pytest.raises(lsc.InvalidArgument):
        sim.move({"base": "30deg"}, time_ms=10)  # no profile: no joint names


def test_kind_is_an_enum_and_still_its_name(sim):
    assert sim.kind is lsc.Kind.SIM
    assert isinstance(sim.kind, lsc.Kind) and sim.kind == "sim"
    assert str(sim.kind) == "sim" and "%s" % sim.kind == "sim"
    assert lsc.Kind("hid") is lsc.Kind.HID
    assert {k.value for k in lsc.Kind} == {"serial", "hid", "sim", "lscd", "lx"}
