"""The package type-checks: mypy --strict over lsc/ (Debian's python3-mypy;
scripts/install-deps.sh installs it), as py.typed promises its users."""
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = os.path.join(os.path.dirname(HERE), "lsc")


def test_mypy_strict(tmp_path):
    pytest.importorskip("mypy", reason="python3-mypy is not installed")
    if not os.path.isdir(PACKAGE):  # the installed package's tests (autopkgtest): no source tree
        pytest.skip("the source tree's lsc/ is not beside the tests")
    r = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental",
                        "--cache-dir", str(tmp_path), PACKAGE],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    assert r.returncode == 0, r.stdout
