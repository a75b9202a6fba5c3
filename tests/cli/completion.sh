#!/usr/bin/env bash
# cli/lscctl.bash-completion: commands, options (global and per command),
# option values, help topics.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
bash_completion=/usr/share/bash-completion/bash_completion
[ -r "$bash_completion" ] || skip "bash-completion is not installed ($bash_completion; package bash-completion)"
# shellcheck disable=SC1090,SC1091
. "$bash_completion"
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
complete_is "calibrate" lscctl ca
complete_is "--check" lscctl calibrate --ch
complete_is "gripper-closed gripper-open" lscctl calibrate --step gr
complete_is "" lscctl reach 1 2 3 --step gr
complete_is "halt help hold" lscctl h
complete_is "all" lscctl unload a
complete_is "all" lscctl --port sim hold a
complete_is "reach read record run" lscctl r
complete_is "reach read record run" lscctl -n --port sim r
complete_is "--speed" lscctl play arm.rob --sp
complete_is "--every" lscctl record arm.rob --ids 1-6 --ev
complete_is "sim" lscctl --port s
complete_is "lx:" lscctl --port l
complete_is "sim" lscctl --port lx:s
complete_is "scan" lscctl --port lx:/dev/ttyUSB0 servo sc
complete_is "motor" lscctl servo mode 1 mo
complete_is "off on" lscctl servo torque 1 o
complete_is "--save" lscctl servo offset 1 5 --sa
complete_is "hid" lscctl --port h
# hid:SERIAL from 'lscctl --json ports' (here a stand-in lscctl with two arms)
lscctl() {
  [ "$*" = "--json ports" ] || return 1
  echo '{"path":"/dev/ttyS0","description":"ttyS0","controller":false}'
  echo '{"path":"/dev/hidraw0","description":"LOBOT","vid":"0483","pid":"5750","serial":"ARM-A","manufacturer":"x","hid":true,"port":"hid:ARM-A","controller":true}'
  echo '{"path":"/dev/hidraw1","description":"LOBOT","vid":"0483","pid":"5750","serial":"B2","manufacturer":"x","hid":true,"port":"hid:B2","controller":true}'
}
complete_is "ARM-A B2" lscctl --port hid:
complete_is "ARM-A" lscctl -p hid:A
unset -f lscctl
complete_is "--time --timeout" lscctl move 1:1500 --tim
complete_is "--timeout --times" lscctl run --time
complete_is "--wait" lscctl run 8 --w
complete_is "--tolerance" lscctl move base:1deg --to
complete_is "--wait" lscctl --arm x.conf move base:1deg --w
complete_is "--arm" lscctl --ar
# --arm NAME: the user's profiles and the installed ones ($LSC_ARMS_DIR), then files
mkdir -p "$TMP/cfg/lsc/arms" "$TMP/inst" "$TMP/cwd"
: >"$TMP/cfg/lsc/arms/mine.conf"
: >"$TMP/inst/xarm.conf"
: >"$TMP/inst/learm.conf"
: >"$TMP/cwd/xray.conf"
before=$failures
(
  cd "$TMP/cwd" || exit 1
  export XDG_CONFIG_HOME="$TMP/cfg" LSC_ARMS_DIR="$TMP/inst"
  complete_is "learm mine xarm xray.conf" lscctl --arm ""
  complete_is "xarm xray.conf" lscctl --port sim --arm x
  complete_is "learm" lscctl convert a.csv b.rob --from-arm xarm --to-arm l
  exit $((failures - before))
) || failures=$((failures + $?))
checks=$((checks + 3))
complete_is "--hid-id" lscctl --hid
complete_is "" lscctl --hid-id ""
complete_is "battery" lscctl --hid-id 1234:5678 ba
complete_is "read set" lscctl offset ""
complete_is "offset" lscctl of
complete_is "--count" lscctl monitor --co
complete_is "--force" lscctl send --fo
complete_is "controller host" lscctl decode --from ""
complete_is "all" lscctl speed a
complete_is "monitor move" lscctl help mo
# help takes one command name, and help is none
complete_is "" lscctl help he
complete_is "" lscctl help move r
complete_is "" lscctl -n help move ""
complete_is "reach read" lscctl rea
complete_is "where" lscctl wh
complete_is "--pitch" lscctl --arm x.conf reach 1 2 3 --pi
complete_is "--step --strict" lscctl reach 1 2 3 --pitch -90 --st
complete_is "" lscctl reach 1 2 3 --roll ""
complete_is "--speed" lscctl move base:1deg --sp
complete_is "--json" lscctl --js
complete_is "--dry-run" lscctl battery --dr
complete_is "115200" lscctl -b 11
finish
