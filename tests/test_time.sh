# shellcheck shell=sh
# Wall-clock waits in shell tests, scaled for slow or busy machines (POSIX sh;
# sourced). The shell twin of tests/test_time.h: `test_ms N` prints N times
# LSC_TEST_TIME_SCALE (a positive integer up to 1000, default 1; anything else
# counts as 1), whatever N's unit. The sanitize and valgrind stages raise it;
# a Debian build daemon or a Raspberry Pi can too. Only waits that bound how
# long a test may take scale, never a figure a test asserts the code keeps.
test_ms() {
  _scale=${LSC_TEST_TIME_SCALE:-1}
  case $_scale in
  '' | *[!0-9]* | ?????*) _scale=1 ;;
  esac
  while :; do # leading zeros: decimal, not octal
    case $_scale in 0?*) _scale=${_scale#0} ;; *) break ;; esac
  done
  if [ "$_scale" -lt 1 ] || [ "$_scale" -gt 1000 ]; then _scale=1; fi
  echo $(($1 * _scale))
}
