"""lsc.Action: action files through the library (docs/action-files.md)."""
import pytest

import lsc
from conftest import wait_until


def sample():
    return lsc.Action([1, 2], [(100, (500, 500)), (400, (700, 300)), (250, (650, 350))])


def test_build():
    a = sample()
    assert a.ids == (1, 2)
    assert len(a) == 3
    assert a.keyframes[1] == lsc.Keyframe(400, (700, 300))
    assert a.duration_ms == 750
    assert list(a)[2].positions == (650, 350)
    assert "3 keyframes" in repr(a)
    a.append(100, [1, 2])
    assert len(a) == 4


@pytest.mark.parametrize("ext", ["csv", "txt"])
def test_round_trip(tmp_path, ext):
    a = sample()
    path = tmp_path / ("1-wave." + ext)
    a.save(path)
    assert lsc.Action.load(str(path)) == a


def test_paths_as_the_os_sees_them(tmp_path):
    """A path is taken as os.fsencode takes it: str (undecodable bytes through
    surrogateescape), bytes, os.PathLike; anything else is refused."""
    import os
    a = sample()
    raw = os.fsencode(str(tmp_path)) + b"/caf\xe9-\xff.csv"  # not UTF-8
    a.save(raw)
    assert lsc.Action.load(raw) == a
    assert lsc.Action.load(os.fsdecode(raw)) == a  # the same file as a str
    assert os.path.exists(raw)
    with pytest.raises(lsc.InvalidArgument, match="str, bytes or os.PathLike"):
        lsc.Action.load(5)
    with pytest.raises(lsc.InvalidArgument, match="NUL"):
        lsc.Action.load(b"a\0b.csv")
    with pytest.raises(lsc.InvalidArgument, match="str, bytes or os.PathLike"):
        lsc.open(5)
    with pytest.raises(lsc.NotFound):
        lsc.open(b"/nonexistent/\xff")


def test_rob_round_trip(tmp_path):
    # .rob: the xArm's six servos in every keyframe
    a = lsc.Action([1, 2, 3, 4, 5, 6], [(0, (500,) * 6), (1000, (100, 200, 300, 400, 500, 600))])
    a.save(tmp_path / "0.rob")
    assert (tmp_path / "0.rob").stat().st_size == 16 + 14 * 2
    assert lsc.Action.load(tmp_path / "0.rob") == a


def test_d6a_round_trip(tmp_path):
    a = sample()
    try:
        a.save(tmp_path / "a.d6a")
    except lsc.Error as e:
        pytest.skip("built without SQLite: %s" % e)
    assert lsc.Action.load(tmp_path / "a.d6a") == a


def test_header_written(tmp_path):
    sample().save(tmp_path / "wave.h")
    assert "wave" in (tmp_path / "wave.h").read_text()


def test_refused_files(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("time_ms,1\n100,notanumber\n")
    with pytest.raises(lsc.InvalidArgument, match=r"bad\.csv: .*2"):
        lsc.Action.load(bad)
    with pytest.raises(lsc.Error) as e:
        lsc.Action.load(tmp_path / "missing.csv")
    assert "missing.csv" in str(e.value)
    with pytest.raises(lsc.InvalidArgument):
        lsc.Action.load(tmp_path / "x.unknown")
    with pytest.raises(lsc.InvalidArgument):
        lsc.Action([7, 8], [(0, (1, 2))]).save(tmp_path / "x.rob")  # servos 1..6 only


def test_invalid():
    with pytest.raises(lsc.InvalidArgument):
        lsc.Action([])
    with pytest.raises(lsc.InvalidArgument):
        lsc.Action(list(range(33)))
    with pytest.raises(lsc.InvalidArgument):
        lsc.Action([1, 1])
    with pytest.raises(lsc.InvalidArgument):
        lsc.Action([256])
    a = lsc.Action([1])
    with pytest.raises(lsc.InvalidArgument):
        a.append(65536, [1])
    with pytest.raises(lsc.InvalidArgument):
        a.append(0, [1, 2])
    with pytest.raises(lsc.InvalidArgument):
        a.append(0, [70000])
    assert len(a) == 0 and a.keyframes == []


def test_play_a_loaded_file(tmp_path):
    sample().save(tmp_path / "a.csv")
    with lsc.open("sim") as c:
        r = c.play(lsc.Action.load(tmp_path / "a.csv"), lead_ms=100)
        assert r.frames == 3
        # (sim follows the real clock: the last move ends as late as it began)
        wait_until(lambda: c.read([1, 2]) == {1: 650, 2: 350}, 30, "the last move's end")
