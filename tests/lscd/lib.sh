# Helpers for lscd's integration tests, sourced by each script once it has
# set mine to its own folder: lscctl's (tests/cli/lib.sh: wait_for, expect,
# sim, ...) and answers.
# Environment: LSCD, LSC_SIM (the built programs), and tests/cli/lib.sh's.
: "${LSCD:?set LSCD to the lscd binary}"
here=$mine/../cli
# shellcheck source=../cli/lib.sh
. "$here/lib.sh"
here=$mine
: "${LSC_SIM:?set LSC_SIM to the lsc-sim binary}"

# answers SOCK: lscctl status through the lscd at SOCK succeeds
answers() { "$LSCCTL" --port "lscd:$1" status >/dev/null 2>&1; }
