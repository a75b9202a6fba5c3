#!/usr/bin/env bash
# The demo, until lscctl exists: builds the project (in build/demo) and runs
# the core's example program (tests/example_core.c, the README's example).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build/demo -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/demo -j 2 >/dev/null
build/demo/tests/example_core
