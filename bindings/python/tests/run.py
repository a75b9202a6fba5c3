#!/usr/bin/env python3
"""Runs the Python bindings' tests with pytest (arguments are pytest's); exit
77 (a skip for ctest) when pytest is not installed (python3-pytest)."""
import os
import sys

try:
    import pytest
except ImportError:
    print("python3-pytest is not installed: the Python bindings' tests are skipped "
          "(scripts/install-deps.sh --all installs it)")
    sys.exit(77)

here = os.path.dirname(os.path.abspath(__file__))
# no cache written into the source tree
sys.exit(pytest.main(["-p", "no:cacheprovider", "--rootdir", here, here] + sys.argv[1:]))
