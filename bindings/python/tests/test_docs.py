"""The docstrings name what the package accepts."""
import lsc


def test_open_names_every_kind_of_port():
    doc = lsc.open.__doc__
    for kind in ('"sim"', '"/dev/ttyUSB0"', '"hid"', '"hid:SERIAL"', '"/dev/hidrawN"',
                 '"lscd:NAME"', '"lscd:PATH"', "$LSC_PORT", "$LSC_LSCD_DIR", "/run/lsc"):
        assert kind in doc, kind
