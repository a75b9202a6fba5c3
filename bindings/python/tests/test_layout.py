"""The structures the bindings pass across the boundary have the C compiler's
layout: sizeof, and each field's offsetof and sizeof, printed by layout.c
(built by CMake as lsc_python_layout, $LSC_LAYOUT; else compiled here with cc
against the installed headers), against the ctypes declarations of
lsc/_native.py. The constants the bindings copy from the headers too."""
import ctypes
import os
import shutil
import subprocess

import pytest

from conftest import HERE, test_s
from lsc import _native as N


@pytest.fixture(scope="module")
def layout(tmp_path_factory):
    exe = os.environ.get("LSC_LAYOUT", "")
    if not exe:
        cc = shutil.which("cc") or shutil.which("gcc")
        if not cc:
            pytest.skip("no layout program: set LSC_LAYOUT, or install a C compiler and "
                        "liblsc-dev to build tests/layout.c")
        flags = []
        if shutil.which("pkg-config"):
            p = subprocess.run(["pkg-config", "--cflags", "lsc"], capture_output=True, text=True)
            if p.returncode == 0:
                flags = p.stdout.split()
        exe = str(tmp_path_factory.mktemp("layout") / "layout")
        p = subprocess.run([cc, "-std=c99", *flags, os.path.join(HERE, "layout.c"), "-o", exe],
                           capture_output=True, text=True, timeout=test_s(120))
        if p.returncode != 0:
            pytest.skip("tests/layout.c does not build here (liblsc-dev missing?): %s"
                        % p.stderr.strip()[-300:])
    out = subprocess.run([exe], check=True, capture_output=True, text=True,
                         timeout=test_s(60)).stdout
    lines = {}
    for line in out.splitlines():
        name, *values = line.split()
        lines[name] = [int(v) for v in values]
    return lines


@pytest.mark.parametrize("name", sorted(N.STRUCTS))
def test_struct(layout, name):
    cls = N.STRUCTS[name]
    assert name in layout, "layout.c does not print %s" % name
    assert layout[name] == [ctypes.sizeof(cls)], "sizeof(%s)" % name
    c_fields = {k.split(".", 1)[1] for k in layout if k.startswith(name + ".")}
    py_fields = {f[0] for f in cls._fields_}
    assert c_fields == py_fields, "the fields of %s" % name
    for field, ctype in cls._fields_:
        f = getattr(cls, field)
        assert layout["%s.%s" % (name, field)] == [f.offset, ctypes.sizeof(ctype)], \
            "offsetof and sizeof of %s.%s" % (name, field)


@pytest.mark.parametrize("name", N.ENUMS)
def test_enum_is_an_int(layout, name):
    assert layout[name] == [ctypes.sizeof(ctypes.c_int)]


def test_constants(layout):
    constants = {k: v for k, v in layout.items() if k.startswith("LSC_")}
    assert constants, "layout.c prints no constant"
    for name, (value,) in constants.items():
        assert getattr(N, name) == value, name


def test_every_struct_is_checked(layout):
    printed = {k for k in layout if "." not in k and not k.startswith("LSC_")}
    assert set(N.STRUCTS) | set(N.ENUMS) <= printed
