"""Bad numbers and points are refused the same way at every entry point,
before anything is sent (lsc._check): a value of the wrong type is an
lsc.InvalidArgument that is also a TypeError (bytes are no point: b'abc'
would be (97, 98, 99) mm); a number refused (out of range, NaN, an
infinity, an int too large for a float or a C type) is an
lsc.InvalidArgument (a ValueError), never a bare OverflowError or a
ValueError of Python's own (an int of more than 4300 digits cannot even be
printed)."""
import pytest

import lsc

XARM = """
gripper 1 bus limits=0..700
wrist-rotate 2 bus limits=-115deg..115deg
wrist 3 bus limits=-115deg..115deg
elbow 4 bus limits=-115deg..115deg
shoulder 5 bus limits=-115deg..115deg
base 6 bus limits=-115deg..115deg
chain: base shoulder elbow wrist wrist-rotate gripper
links: height=64.7mm upper=98.8mm fore=94.7mm tool=158.8mm
"""

HUGE = 10**400
ENORMOUS = 10**5000  # more digits than Python will print
NAN, INF = float("nan"), float("inf")


@pytest.fixture
def c():
    c = lsc.open("sim", arm=lsc.Arm.parse(XARM, "xarm.conf"))
    c.sent = []
    c.trace(lambda d, frame: c.sent.append(frame) if d == "tx" else None)
    yield c
    assert c.sent == []  # nothing of what was refused went out
    c.close()


def refused(call, wrong_type):
    """call() raises lsc.InvalidArgument, a TypeError exactly when wrong_type."""
    with pytest.raises(lsc.InvalidArgument) as e:
        call()
    assert isinstance(e.value, TypeError) == wrong_type, (e.value, wrong_type)
    assert str(e.value)  # a message (printable: no 5000-digit int in it)
    return e.value


def test_points(c):
    for bad in (b"abc", bytearray(b"abc"), memoryview(b"abc"), "abc", 5, None):
        e = refused(lambda: c.reach(bad), True)
        assert "a point is (x, y, z)" in str(e)
    refused(lambda: c.reach((1, 2)), False)
    refused(lambda: c.reach((1, 2, 3, 4)), False)
    for bad in (HUGE, -HUGE, ENORMOUS, NAN, INF, -INF):
        refused(lambda: c.reach((bad, 0, 0)), False)
        refused(lambda: c.reach((200, 0, 100), pitch=bad), False)
        refused(lambda: c.reach((200, 0, 100), roll=bad), False)
        refused(lambda: c.reach((200, 0, 100), speed=bad), False)
        refused(lambda: c.reach((200, 0, 100), line=True, step_mm=bad), False)
        refused(lambda: c.arm.inverse((bad, 0, 0)), False)
        refused(lambda: c.arm.forward([bad, 0, 0, 0, 0]), False)
    for bad in (True, "1", b"1", None, [1]):
        refused(lambda: c.reach((bad, 0, 0)), True)
        if bad is not None:  # (pitch=None: none given)
            refused(lambda: c.reach((200, 0, 100), pitch=bad), True)
        refused(lambda: c.arm.forward([bad, 0, 0, 0, 0]), True)
    e = refused(lambda: c.reach((HUGE, 0, 0)), False)
    assert "x: an int of 401 digits is too large" in str(e)


def test_integers(c):
    for bad, wrong_type in ((HUGE, False), (ENORMOUS, False), (-1, False), (70000, False),
                            (True, True), (1.0, True), ("1", True), (b"1", True)):
        refused(lambda: c.move({1: 500}, time_ms=bad), wrong_type)
        refused(lambda: c.move({1: 500}, time_ms=100, tolerance=bad), wrong_type)
        refused(lambda: c.run(bad), wrong_type)
        refused(lambda: c.speed(1, bad), wrong_type)
        refused(lambda: c.reach((200, 0, 100), time_ms=bad), wrong_type)
        if not isinstance(bad, str):  # ("1": servo 1 by its id as text)
            refused(lambda: c.read([bad]), wrong_type)
        refused(lambda: c.play(lsc.Action([1], [(100, [500])]), lead_ms=bad), wrong_type)
        refused(lambda: lsc.Action([1]).append(bad, [500]), wrong_type)
        refused(lambda: lsc.Action([1]).append(100, [bad]), wrong_type)
        if bad != 70000:
            refused(lambda: lsc.open("sim", timeout_ms=bad), wrong_type)
    for bad in (-1, HUGE, ENORMOUS):
        refused(lambda: lsc.Action([bad]), False)
    refused(lambda: lsc.Action([True]), True)
    # a target: a position (int), an angle (float), or text
    for bad in (HUGE, ENORMOUS, -HUGE):
        refused(lambda: c.move({1: bad}, time_ms=100), False)
        refused(lambda: c.move({bad: 500}, time_ms=100), False)
    for bad in (True, b"500", [500]):
        refused(lambda: c.move({1: bad}, time_ms=100), True)
    refused(lambda: c.move({1: None}, time_ms=100), False)  # (None: read()'s "no joint")
    refused(lambda: c.move({"base": NAN}, time_ms=100), False)
    refused(lambda: c.move({"base": INF}, time_ms=100), False)


def test_timeouts(c):
    for bad in (-1, NAN, INF, HUGE, -INF):
        refused(lambda: c.notification(timeout=bad), False)
        refused(lambda: c.wait_group(timeout=bad), False)
        refused(lambda: c.poll(bad), False)
    for bad in ("1", True, b"1", [1]):
        refused(lambda: c.notification(timeout=bad), True)


def test_the_right_values_still_go(c):
    """The checks let every good value through, ints of other kinds
    (anything with __index__) included."""
    class Index:
        def __init__(self, v):
            self.v = v

        def __index__(self):
            return self.v
    c.trace(None)
    c.move({Index(6): Index(600)}, time_ms=Index(100))
    c.poll(0.2)
    assert c.read([6]) == {6: 600}
    assert c.reach((200, 0, 100), pitch=-45.0, time_ms=100)
    assert c.reach([200.0, 0, 100], speed=90)
    c.sent = []


def test_bytes_names_and_lists(c):
    """Raw parameters are bytes (an int would be that many zero bytes), a
    servo list is iterable, a name is text, bytes or a path."""
    for bad in (5, HUGE, "ab", None):
        refused(lambda: c.send(1, bad), True)
        refused(lambda: c.request(15, bad), True)
    for bad in ([256], [-1], [HUGE]):
        refused(lambda: c.send(1, bad), False)
    refused(lambda: c.send(1, [True]), True)
    refused(lambda: c.read(None), True)
    refused(lambda: c.unload(5.0), True)
    refused(lambda: c.move([(1, 500)], time_ms=100), True)
    refused(lambda: lsc.open(5), True)
    refused(lambda: lsc.Arm(None), True)
    c.trace(None)
    assert c.request(15, [], 15) == c.request(15, b"")  # a list of ints is bytes too
    c.sent = []
