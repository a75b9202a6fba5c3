#!/usr/bin/env bash
# cli/lscctl.bash-completion: commands, options (global and per command),
# option values, help topics.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
# shellcheck disable=SC1091
. /usr/share/bash-completion/bash_completion
# shellcheck disable=SC1091
. "$here/../../cli/lscctl.bash-completion"

# complete WANT WORDS...: completing the last word of "WORDS" gives WANT
complete_is() {
  local want=$1; shift
  COMP_WORDS=("$@")
  COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
  COMP_LINE="${COMP_WORDS[*]}"
  COMP_POINT=${#COMP_LINE}
  COMPREPLY=()
  _lscctl lscctl "${COMP_WORDS[COMP_CWORD]}" "${COMP_WORDS[COMP_CWORD - 1]}"
  checks=$((checks + 1))
  local got
  got=$(printf '%s\n' "${COMPREPLY[@]}" | LC_ALL=C sort | tr '\n' ' ')
  [ "$got" = "$want " ] || fail "completing '$*': got '$got', want '$want '"
}

complete_is "battery" lscctl ba
complete_is "read run" lscctl r
complete_is "read run" lscctl -n --port sim r
complete_is "sim" lscctl --port s
complete_is "--time --timeout" lscctl move 1:1500 --tim
complete_is "--timeout --times" lscctl run --time
complete_is "--wait" lscctl run 8 --w
complete_is "--tolerance" lscctl move base:1deg --to
complete_is "--wait" lscctl --arm x.conf move base:1deg --w
complete_is "--arm" lscctl --ar
complete_is "read set" lscctl offset ""
complete_is "offset" lscctl of
complete_is "--count" lscctl monitor --co
complete_is "--force" lscctl send --fo
complete_is "controller host" lscctl decode --from ""
complete_is "all" lscctl speed a
complete_is "monitor move" lscctl help mo
complete_is "--json" lscctl --js
complete_is "--dry-run" lscctl battery --dr
complete_is "115200" lscctl -b 11
finish
