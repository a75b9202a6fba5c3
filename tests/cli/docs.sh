#!/usr/bin/env bash
# Every shell example of README.md, docs/*.md, cli/lscctl.1 and cli/lsc-sim.1 runs and
# shows what the document shows: tests/cli/docs.py reads the
# examples out of the documents (the rules are at its top).
# Environment: LSCCTL, LSC_SIM (the built programs), SOURCE_DIR.
set -u
here=$(cd "$(dirname "$0")" && pwd)
: "${LSCCTL:?}" "${LSC_SIM:?}" "${SOURCE_DIR:?}"
command -v python3 >/dev/null || { echo "SKIP: python3 is not installed (scripts/install-deps.sh --all)"; exit 77; }
command -v stdbuf >/dev/null || { echo "SKIP: stdbuf is not installed (package coreutils)"; exit 77; }
exec python3 "$here/docs.py" "$LSCCTL" "$LSC_SIM" "$SOURCE_DIR" "$@"
