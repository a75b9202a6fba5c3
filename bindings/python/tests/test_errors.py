"""Errors are exceptions with the library's one-line message; invalid
arguments are refused before anything is sent (ctypes would otherwise wrap an
out-of-range number silently)."""
import os

import pytest

import lsc
from conftest import child_env, run_python


def nothing_sent(c, call):
    """Runs call(c), which must raise lsc.InvalidArgument having sent nothing."""
    sent = []
    c.trace(lambda d, f: sent.append(f))
    with pytest.raises(lsc.InvalidArgument) as e:
        call(c)
    c.trace(None)
    assert sent == [], "frames went out: %r" % sent
    assert isinstance(e.value, ValueError)
    assert e.value.code == -1
    assert str(e.value) and "\n" not in str(e.value)
    return e.value


@pytest.mark.parametrize("call", [
    lambda c: c.move({}, time_ms=100),
    lambda c: c.move({1: 1500}, time_ms=-1),
    lambda c: c.move({1: 1500}, time_ms=65536),
    lambda c: c.move({1: 70000}, time_ms=100),
    lambda c: c.move({1: -1}, time_ms=100),
    lambda c: c.move({256: 1500}, time_ms=100),
    lambda c: c.move({1: 1.5}, time_ms=100),
    lambda c: c.move({1: True}, time_ms=100),
    lambda c: c.move({1: "30deg"}, time_ms=100),  # no profile: positions only
    lambda c: c.move({1: 1500}, time_ms=1.5),
    lambda c: c.move([(1, 1500)], time_ms=100),
    lambda c: c.move({i: 1500 for i in range(84)}, time_ms=100),
    lambda c: c.move({1: 1500}, time_ms=100, tolerance=-1),
    lambda c: c.read([]),
    lambda c: c.read([300]),
    lambda c: c.read(["1", 1]),
    lambda c: c.read(list(range(85))),
    lambda c: c.read([None]),
    lambda c: c.run(256),
    lambda c: c.run(1, times=65536),
    lambda c: c.run(-1),
    lambda c: c.run(1, wait=True, timeout=-1),
    lambda c: c.run(1, wait=True, timeout=float("nan")),
    lambda c: c.speed(1, 0),
    lambda c: c.speed(1, 65536),
    lambda c: c.speed(300, 100),
    lambda c: c.unload([]),
    lambda c: c.unload([1, 1]),
    lambda c: c.offsets([]),
    lambda c: c.adjust_offset(1, 128),
    lambda c: c.adjust_offset(1, -129),
    lambda c: c.send(256),
    lambda c: c.send(27, b"\x01"),  # every servo's id: needs force
    lambda c: c.send(3, bytes(254)),
    lambda c: c.request(15, reply_cmd=300),
    lambda c: c.poll(-1),
    lambda c: c.poll(None),
    lambda c: c.notification(timeout="2"),
    lambda c: c.play("0.rob"),
    lambda c: c.play(lsc.Action([1]), lead_ms=100),
    lambda c: c.play(lsc.Action([1], [(0, (1500,))]), speed=0),
    lambda c: c.play(lsc.Action([1], [(0, (1500,))]), times=0),
    lambda c: c.play(lsc.Action([1], [(0, (1500,))]), lead_ms=70000),
    lambda c: c.record([1], every_ms=0, count=1),
    lambda c: c.record([1], every_ms=100, count=0),
])
def test_refused_before_sending(sim, call):
    nothing_sent(sim, call)


def test_message_is_the_library_line(sim):
    e = nothing_sent(sim, lambda c: c.move({i: 1500 for i in range(84)}, time_ms=100))
    assert "servo_move" in str(e) or "83" in str(e)


def test_not_found():
    with pytest.raises(lsc.NotFound) as e:
        lsc.open("/dev/lsc-python-test-no-such-port")
    assert "/dev/lsc-python-test-no-such-port" in str(e.value)
    assert e.value.code == -10
    assert isinstance(e.value, lsc.Error)


def test_not_a_serial_port(tmp_path):
    f = tmp_path / "plain-file"
    f.write_text("")
    with pytest.raises(lsc.Error) as e:
        lsc.open(str(f))
    assert str(f) in str(e.value)


def test_open_arguments():
    with pytest.raises(lsc.InvalidArgument):
        lsc.open("sim", timeout_ms=0)
    with pytest.raises(lsc.InvalidArgument):
        lsc.open("sim", baud=-1)
    with pytest.raises(lsc.InvalidArgument):
        lsc.open("sim", hid_vid=0x10000)
    with pytest.raises(lsc.InvalidArgument):
        lsc.open(42)
    with pytest.raises(lsc.InvalidArgument):
        lsc.open("sim\0x")


def test_no_controller_present(tmp_path):
    # LSC_PORT set to a path that does not exist: the open names it
    r = run_python("import lsc\ntry:\n    lsc.open()\nexcept lsc.Error as e:\n"
                   "    print(type(e).__name__, e)\n",
                   env=child_env(LSC_PORT=str(tmp_path / "none")))
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("NotFound ") and str(tmp_path / "none") in r.stdout


def test_hierarchy():
    for cls in (lsc.Timeout, lsc.Busy, lsc.NotFound, lsc.PermissionDenied,
                lsc.InvalidArgument, lsc.LinkError):
        assert issubclass(cls, lsc.Error)
    assert issubclass(lsc.Timeout, TimeoutError)
    assert issubclass(lsc.PermissionDenied, PermissionError)
    assert issubclass(lsc.InvalidArgument, ValueError)
    e = lsc.Timeout("no reply", -6)
    assert str(e) == "no reply" and e.code == -6 and e.message == "no reply"


def test_permission_hint_names_the_rule():
    from lsc.errors import error_for
    import lsc._native as N
    none = N.LSC_DEVICE_CAUSE_NONE
    e = error_for(-11, "cannot open /dev/hidraw0: Permission denied", hid=True, cause=none)
    assert isinstance(e, lsc.PermissionDenied)
    assert "60-lsc.rules" in str(e) and "plugdev" in str(e)
    e = error_for(-11, "cannot open /dev/ttyUSB0: Permission denied", cause=none)
    assert "dialout" in str(e)
    # the library's own advice (its cause says it gave some) is kept as it is,
    # whatever its words
    e = error_for(-11, "denied: ask the owner", hid=True, cause=N.LSC_DEVICE_CAUSE_ACCESS)
    assert str(e) == "denied: ask the owner"
    # no device's error (a file's): no device's hint
    e = error_for(-11, "profile.conf: Permission denied", file=True)
    assert str(e) == "profile.conf: Permission denied"


def test_library_missing():
    r = run_python("import lsc", env=child_env(LSC_LIBRARY="/nonexistent/liblsc.so.2"))
    assert r.returncode == 1
    assert "ImportError: lsc: cannot load LSC_LIBRARY=/nonexistent/liblsc.so.2" in r.stderr


def test_library_too_old(tmp_path):
    # a library without the device layer (here: the C library itself, libc)
    r = run_python("import lsc", env=child_env(LSC_LIBRARY="libc.so.6"))
    assert r.returncode == 1
    assert "lacks lsc_strerror" in r.stderr and "older than these bindings" in r.stderr


def test_library_advice_fits_the_install():
    from lsc._native import install_advice
    # Debian's python3-lsc: the library is a package
    debian = install_advice("/usr/lib/python3/dist-packages/lsc")
    assert debian == "apt install liblsc2"
    assert "0.4.0 or later" in install_advice("/usr/lib/python3/dist-packages/lsc", newer=True)
    # from the source tree (a venv's pip install, PYTHONPATH): no apt, the
    # library of a build or an install of that tree
    for where in ("/home/u/venv/lib/python3.11/site-packages/lsc", "/src/lsc/bindings/python/lsc"):
        advice = install_advice(where)
        assert "apt" not in advice
        assert "cmake --install" in advice and "ldconfig" in advice and "LSC_LIBRARY" in advice
    assert install_advice("/src/lsc/bindings/python/lsc", newer=True).startswith("a newer library")


def test_library_too_old_says_what_to_install():
    # the advice of the package under test, wherever it is installed
    from lsc._native import install_advice
    r = run_python("import lsc", env=child_env(LSC_LIBRARY="libc.so.6"))
    assert r.returncode == 1
    assert install_advice(os.path.dirname(os.path.abspath(lsc.__file__)), newer=True) in r.stderr


def test_version_is_the_package_metadata():
    pyproject = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                             "pyproject.toml")
    if not os.path.exists(pyproject):
        pytest.skip("no pyproject.toml beside the tests (an installed package's test)")
    with open(pyproject) as f:
        assert 'version = "%s"' % lsc.__version__ in f.read()
