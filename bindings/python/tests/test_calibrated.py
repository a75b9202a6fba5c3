"""lsc.open without an arm uses the profile calibrated for the arm on that
controller (lscctl calibrate: $XDG_CONFIG_HOME/lsc/arms/KEY.conf, KEY "sim"
for the virtual controller); arm= and $LSC_ARM still win."""
import lsc

CALIBRATED = """# calibrate home: 2026-11-29 10:00 UTC, from xarm.conf
base 6 bus offset=+23
shoulder 5 bus
"""


def test_calibrated_profile_found(tmp_path, monkeypatch):
    arms = tmp_path / "lsc" / "arms"
    arms.mkdir(parents=True)
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    monkeypatch.delenv("LSC_ARM", raising=False)
    monkeypatch.delenv("LSC_PORT", raising=False)
    with lsc.open("sim") as c:  # none yet
        assert c.arm is None
    (arms / "sim.conf").write_text(CALIBRATED)
    with lsc.open("sim") as c:
        assert c.arm.names() == ["base", "shoulder"]
        assert c.arm.path == str(arms / "sim.conf")
        c.move({6: 523}, time_ms=0, wait=True)
        assert c.read(["base"], degrees=True) == {"base": 0.0}
    monkeypatch.setenv("LSC_PORT", "sim")  # the name from $LSC_PORT
    with lsc.open() as c:
        assert c.arm.names() == ["base", "shoulder"]
    (tmp_path / "other.conf").write_text("hand 1 bus\n")
    with lsc.open("sim", arm=str(tmp_path / "other.conf")) as c:
        assert c.arm.names() == ["hand"]
    monkeypatch.setenv("LSC_ARM", str(tmp_path / "other.conf"))
    with lsc.open("sim") as c:
        assert c.arm.names() == ["hand"]
