#!/usr/bin/env bash
# tests/cli/docs.py itself, on a document of its own: --section (only those
# headings, in the order given; a missing one or one without a command fails),
# a file: NAME block (written for the commands after it),
# and --here (the current directory, the programs on PATH, the environment
# passed through, export and cd kept, stdout compared only where output is
# shown, a background lsc-sim --link waited for and stopped), and that a
# drifted example fails. Environment: LSCCTL, LSC_SIM (the built programs).
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
. "$here/lib.sh"
: "${LSC_SIM:?}"
command -v python3 >/dev/null || skip "python3 is not installed (scripts/install-deps.sh --all)"
docs() { run python3 "$here/docs.py" "$@"; }
has() { grep -qF -- "$1" "$OUT" || fail "$2: no '$1' in: $(cat "$OUT" "$ERR")"; }

mkdir -p "$TMP/doc/sub" "$TMP/bin"
echo "in sub" >"$TMP/doc/sub/here.txt"
printf '#!/bin/sh\necho tool ran\n' >"$TMP/bin/tool"
chmod +x "$TMP/bin/tool"
ln -s "$LSC_SIM" "$TMP/bin/lsc-sim"
cat >"$TMP/doc/doc.md" <<'DOC'
# A document

## One

```sh
$ export GREETING=hello WHO=$FROM_ENV
$ echo "$GREETING $WHO"
hello reader
$ cd sub
$ cat here.txt
in sub
$ tool                           # found on PATH
tool ran
$ echo noise >&2; echo shown     # stderr is not compared
shown
$ echo what a build prints       # shown without output: not compared
```

### Two

```sh
$ echo two
two
```

## Fails

```sh
$ false
```

## Drift

```sh
$ echo actual
expected
```

## Prose only

```c
int x;
```

## Not run only

<!-- docs-test: not run: the reason -->
```sh
$ reboot
```

## File

<!-- docs-test: file: greet.txt -->
```text
hello from a file
```

```sh
$ cat greet.txt
hello from a file
```

## Background

```sh
$ lsc-sim --link board >/dev/null &
$ test -e board && echo there
there
$ kill %1
```
DOC
cd "$TMP/doc" || exit 1
export PATH="$TMP/bin:$PATH" FROM_ENV=reader

checks=$((checks + 1))
docs --here --section Two --section One doc.md
[ "$rc" = 0 ] || fail "--here --section Two --section One: exit $rc: $(cat "$OUT" "$ERR")"
has 'ok   doc.md:' "--here"
grep -q 'false' "$OUT" && fail "--section ran a section it was not given: $(cat "$OUT")"
[ "$(grep -n 'echo two\|export GREETING' "$OUT" | cut -d: -f1 | tr '\n' ' ')" = "1 2 " ] ||
  fail "--section: not in the order given: $(cat "$OUT")"

checks=$((checks + 1))
docs --here --section Background doc.md
[ "$rc" = 0 ] || fail "--here, lsc-sim in the background: exit $rc: $(cat "$OUT" "$ERR")"
[ ! -e board ] || fail "kill %1 did not stop lsc-sim (./board is still there)"

# a file: NAME block is written for the commands after it
checks=$((checks + 1))
docs --here --section File doc.md
[ "$rc" = 0 ] || fail "--here --section File: exit $rc: $(cat "$OUT" "$ERR")"
has 'file doc.md:' "a file: NAME block"

# failures: exit 1 and the reason
for c in "Missing|no \`\`\`sh block under a heading 'Missing'" \
         "Prose only|no \`\`\`sh block under a heading 'Prose only'" \
         "Not run only|'Not run only' has no command to run" \
         "Fails|exit 1, the document says 0" \
         "Drift|output differs"; do
  checks=$((checks + 1))
  docs --here --section "${c%%|*}" doc.md
  [ "$rc" = 1 ] || fail "--section ${c%%|*}: exit $rc, want 1: $(cat "$OUT" "$ERR")"
  has "${c#*|}" "--section ${c%%|*}"
done

checks=$((checks + 1))
docs --here
[ "$rc" = 2 ] || fail "--here without a document: exit $rc, want 2"
checks=$((checks + 1))
docs --bogus doc.md
[ "$rc" = 2 ] || fail "an unknown option: exit $rc, want 2"
finish
