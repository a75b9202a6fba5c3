#!/usr/bin/env python3
"""Runs the shell examples of README.md and the man pages and compares their
output with what the documents show (documentation that is executed).

Usage: docs.py [--section HEADING]... LSCCTL LSC_SIM SOURCE_DIR [DOCUMENT...]
       docs.py --here [--section HEADING]... DOCUMENT...
(default documents: README.md, cli/lscctl.1, cli/lsc-sim.1 and every
docs/*.md). Exit 0 when every
example matches, 1 otherwise (each mismatch is printed), 2 for a usage error.

--section HEADING (repeatable; Markdown): only the ```sh blocks under that
heading (the text of a heading of any level, without the #s; up to the next
heading), sections in the order given, all in one session. A heading that is
not there, or has no command, fails.

--here: a reader's terminal in the current directory instead of a scratch
one: the programs are the ones on PATH (or as the document writes them,
./lsc-serial), the environment is passed through (PREFIX...). Only stdout is
compared (stderr is shown when a command fails), and only for a command that
shows output: a command shown without output (a build) must exit as expected,
its messages are not compared. (examples/*/README.md, run by
tests/check-install.sh, scripts/package-test.sh, tests/embedded/run-stm32.sh.)

The documents are the source; this reads the examples out of them:
- Markdown (README.md, docs/*.md): every ```sh block. Man pages: every .nf/.fi block of the
  EXAMPLES section (roff escapes \\- \\e \\(aq \\& undone, the block's common
  indentation removed).
- A block may be preceded by a marker: in Markdown the comment
  <!-- docs-test: KIND -->, in roff the comment line .\\" docs-test: KIND
  (blank lines between are allowed). KIND is
    run (the default)  lines starting with "$ " are commands, run in order;
                       the lines up to the next command are its expected
                       output (stdout and stderr together); a block with no
                       "$ " line is an error
    dry-run: WHY       needs hardware: every command (a "$ " line, or every
                       line) runs with -n after each lscctl, must exit as
                       expected; its output is not compared (it shows frames,
                       not the board's answer)
    not run: WHY       not executed (the reason is printed)
    file: NAME         (Markdown, before a block that is not ```sh: a
                       program's source) the block is written to the file
                       NAME in the working directory, in the document's
                       order, for the commands after it (cc NAME ...)
- The exit status a command must have is 0, or N when its comment says
  "exit N".
- All examples of one document run in one session, in the document's order,
  with stdin closed: lscctl and lsc-sim are the built programs (and lscd,
  when $LSCD names it), the working
  directory is a scratch directory where examples/ is the source tree's
  (--here: see above), cc is $DOCS_CC when set (the build's compiler; with
  PKG_CONFIG_PATH, set by the test, `pkg-config lsc` names the build's
  library; with LSC_LIBRARY and PYTHONPATH, also set by the test, `import
  lsc` is the tree's Python package over the build's library), the
  environment without LSC_* variables (but LSC_TEST_TIME_SCALE and
  LSC_LIBRARY), "export ...", "unset ..." and "cd ..." change the
  variables and directory of the commands after them as in a shell, and
  "/tmp/" in a command is the session's own scratch directory (several
  suites may run at once), shown as /tmp/ in the output again.
- A command ending in "&" runs in the background (its own process group);
  when it has --link PATH, the next command waits until PATH exists; when it
  is lscctl, until it holds its port's lock and sleeps (it opened the port,
  discarded what was there, and waits for input), or, with --port lscd:...,
  until lscd lists it as a client (lscctl status); when it is lscd, until
  lscd answers on its socket (--socket, --instance or the NAME of --port).
  "kill %N" (or %%, the latest job) first waits until the job printed as many
  lines as the document shows after the kill, then sends SIGTERM to the job's
  process group; the job's output (stdout and stderr) is compared with those
  lines. "kill -SIGNAL %N" sends SIGNAL and changes nothing else. "wait %N"
  waits for the job to end; its output and exit status are compared.
- Normalised on both sides, nothing else: /dev/pts/NUMBER reads /dev/pts/N;
  lsc-sim --log's time ("lsc-sim: 0.503434 rx ...") reads "lsc-sim: T";
  the time of record's "keyframe K +MS ms:" reads "+T ms".
Waits scale with LSC_TEST_TIME_SCALE (a positive integer, default 1).
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SCALE = max(1, int(os.environ.get("LSC_TEST_TIME_SCALE", "1") or "1"))
DEADLINE_S = 30 * SCALE      # a condition a step waits for
COMMAND_LIMIT_S = 120 * SCALE  # a safety limit for a hung command

MARKER_MD = re.compile(r"^<!--\s*docs-test:\s*(.*?)\s*-->\s*$")
MARKER_ROFF = re.compile(r'^\.\\"\s*docs-test:\s*(.*?)\s*$')


class Example:
    """One block: where it is, its kind (run, dry-run, not run), its lines."""

    def __init__(self, doc, line, kind, why, lines, heading=None):
        self.doc, self.line, self.kind, self.why, self.lines = doc, line, kind, why, lines
        self.heading = heading  # the Markdown heading the block is under

    def where(self):
        return "%s:%d" % (self.doc, self.line)


def parse_marker(text):
    """'run' / 'dry-run: WHY' / 'not run: WHY' -> (kind, why)."""
    kind, _, why = text.partition(":")
    kind = kind.strip()
    if kind not in ("run", "dry-run", "not run", "file"):
        raise ValueError("unknown docs-test kind %r (run, dry-run: WHY, not run: WHY, file: NAME)"
                         % kind)
    if kind != "run" and not why.strip():
        raise ValueError("docs-test: %s needs a reason after the colon" % kind)
    return kind, why.strip()


def markdown_examples(name, text):
    out = []
    lines = text.split("\n")
    i = 0
    marker = None
    heading = None
    while i < len(lines):
        line = lines[i]
        m = MARKER_MD.match(line)
        h = re.match(r"#+ (.*)$", line)
        if m:
            marker = (m.group(1), i + 1)
        elif h:
            heading = h.group(1).strip()
            if marker:
                raise ValueError("%s:%d: a docs-test marker not followed by a ```sh block" % (name, marker[1]))
        elif line.startswith("```"):
            info = line[3:].strip()
            start = i + 2  # the first line of the block, counted from 1
            body = []
            i += 1
            while i < len(lines) and not lines[i].startswith("```"):
                body.append(lines[i])
                i += 1
            kind, why = parse_marker(marker[0]) if marker else ("run", "")
            if info == "sh" and kind != "file":
                out.append(Example(name, start, kind, why, body, heading))
            elif marker and kind == "file" and info != "sh" and re.fullmatch(r"[\w.-]+", why):
                out.append(Example(name, start, kind, why, body, heading))
            elif marker:
                raise ValueError("%s:%d: a docs-test marker before a ```%s block" % (name, marker[1], info))
            marker = None
        elif line.strip() and marker:
            raise ValueError("%s:%d: a docs-test marker not followed by a ```sh block" % (name, marker[1]))
        i += 1
    return out


def roff_unescape(s):
    return s.replace("\\-", "-").replace("\\(aq", "'").replace("\\&", "").replace("\\e", "\\")


def roff_examples(name, text):
    out = []
    lines = text.split("\n")
    in_examples = False
    marker = None
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith(".SH"):
            in_examples = line.split(None, 1)[1:] == ["EXAMPLES"]
        elif in_examples:
            m = MARKER_ROFF.match(line)
            if m:
                marker = m.group(1)
            elif line.startswith(".nf"):
                start = i + 2  # the first line of the block, counted from 1
                body = []
                i += 1
                while i < len(lines) and not lines[i].startswith(".fi"):
                    body.append(roff_unescape(lines[i]))
                    i += 1
                indent = min((len(b) - len(b.lstrip(" ")) for b in body if b.strip()), default=0)
                body = [b[indent:] for b in body]
                kind, why = parse_marker(marker) if marker else ("run", "")
                out.append(Example(name, start, kind, why, body))
                marker = None
        i += 1
    return out


def normalise(text):
    text = re.sub(r"/dev/pts/[0-9]+", "/dev/pts/N", text)
    text = re.sub(r"^lsc-sim: [0-9]+\.[0-9]+ ", "lsc-sim: T ", text, flags=re.M)
    return re.sub(r"^keyframe ([0-9]+) \+[0-9]+ ms:", r"keyframe \1 +T ms:", text, flags=re.M)


def split_comment(cmd):
    """The command without a trailing comment (a # after a blank, outside
    quotes), and the comment."""
    quote = None
    for i, c in enumerate(cmd):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or cmd[i - 1] in " \t"):
            return cmd[:i].rstrip(), cmd[i + 1:]
    return cmd.rstrip(), ""


def wanted_status(comment):
    m = re.search(r"\bexit (\d+)\b", comment)
    return int(m.group(1)) if m else 0


def commands_of(ex):
    """[(line number, command, [expected output lines])] of a block. In a
    dry-run block without "$ " lines every line is a command."""
    plain = ex.kind == "dry-run" and not any(l.startswith("$ ") for l in ex.lines)
    cmds = []
    for n, line in enumerate(ex.lines):
        if plain or line.startswith("$ "):
            if line.strip():
                cmds.append((ex.line + n, line[0 if plain else 2:], []))
        elif cmds:
            cmds[-1][2].append(line)
        elif line.strip():
            raise ValueError("%s: output before any '$ ' command: %r" % (ex.where(), line))
    if not cmds:
        raise ValueError("%s: a run block without a '$ ' command (mark it docs-test: not run: WHY)"
                         % ex.where())
    return cmds


class Session:
    """The shell a reader types the examples of one document into. here: in
    the current directory with the programs on PATH, stdout apart from stderr
    (--here); otherwise lscctl and lsc-sim are the given programs, in a
    scratch directory, stdout and stderr together."""

    def __init__(self, lscctl, lsc_sim, source, here=False):
        self.here = here
        self.dir = tempfile.mkdtemp(prefix="lsc-docs-")
        self.tmp = os.path.join(self.dir, "tmp")
        os.mkdir(self.tmp)
        self.env = {k: v for k, v in os.environ.items()
                    if not k.startswith("LSC_") or k in ("LSC_TEST_TIME_SCALE", "LSC_LIBRARY")}
        self.env["LC_ALL"] = "C"
        if here:
            self.cwd = os.getcwd()
        else:
            self.cwd = os.path.join(self.dir, "work")
            bindir = os.path.join(self.dir, "bin")
            for d in (self.cwd, bindir):
                os.mkdir(d)
            os.symlink(os.path.join(os.path.abspath(source), "examples"), os.path.join(self.cwd, "examples"))
            os.symlink(os.path.abspath(lscctl), os.path.join(bindir, "lscctl"))
            os.symlink(os.path.abspath(lsc_sim), os.path.join(bindir, "lsc-sim"))
            if os.environ.get("LSCD"):
                os.symlink(os.path.abspath(os.environ["LSCD"]), os.path.join(bindir, "lscd"))
            if os.environ.get("DOCS_CC"):
                os.symlink(os.environ["DOCS_CC"], os.path.join(bindir, "cc"))
            self.env["PATH"] = bindir + os.pathsep + os.environ.get("PATH", "/usr/bin:/bin")
        self.jobs = {}  # number -> (Popen, stdout file, stderr file or None)

    def write(self, name, lines):
        """A file: the block of a file: NAME marker."""
        with open(os.path.join(self.cwd, name), "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")

    def local(self, cmd):
        return cmd.replace("/tmp/", self.tmp + "/")

    def shown(self, text):
        return text.replace(self.tmp + "/", "/tmp/")

    def errors(self):
        """Where a command's stderr goes: apart (--here) or with stdout."""
        return subprocess.PIPE if self.here else subprocess.STDOUT

    def run(self, cmd, dry_run):
        """(status, output, stderr if apart) of one command line, or raises on
        a hang."""
        body, comment = split_comment(cmd)
        if dry_run:
            body = re.sub(r"(^|[|;&(]\s*|\$\()lscctl ", r"\1lscctl -n ", body)
        body = self.local(body)
        if body.endswith("&") and not body.endswith("&&"):
            return self.background(body[:-1].rstrip())
        if re.match(r"(export|unset|cd)(\s|$)", body):
            return self.change_shell(body)
        p = subprocess.run(["bash", "-o", "pipefail", "-c", body], cwd=self.cwd, env=self.env,
                           stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=self.errors(),
                           timeout=COMMAND_LIMIT_S)
        return p.returncode, self.shown(decode(p.stdout)), self.shown(decode(p.stderr or b""))

    def change_shell(self, body):
        """export / unset / cd: bash runs it, then says its environment and
        directory, which the commands after it get."""
        state = os.path.join(self.dir, "state")
        script = '%s || exit\nenv -0 >"$1"; printf "%%s" "$PWD" >"$1.cwd"' % body
        p = subprocess.run(["bash", "-c", script, "bash", state], cwd=self.cwd, env=self.env,
                           stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=self.errors(),
                           timeout=COMMAND_LIMIT_S)
        if p.returncode == 0:
            with open(state, "rb") as f:
                pairs = (v.decode("utf-8", "replace").partition("=") for v in f.read().split(b"\0") if v)
                self.env = {k: v for k, _, v in pairs if k not in ("_", "SHLVL", "OLDPWD")}
            with open(state + ".cwd") as f:
                self.cwd = f.read()
        return p.returncode, self.shown(decode(p.stdout)), self.shown(decode(p.stderr or b""))

    def background(self, body):
        n = max(self.jobs, default=0) + 1
        out = open(os.path.join(self.dir, "job%d.out" % n), "w+b")
        err = open(os.path.join(self.dir, "job%d.err" % n), "w+b") if self.here else None
        p = subprocess.Popen(["bash", "-o", "pipefail", "-c", body], cwd=self.cwd, env=self.env,
                             stdin=subprocess.DEVNULL, stdout=out, stderr=err or subprocess.STDOUT,
                             start_new_session=True)
        self.jobs[n] = (p, out, err)
        via = re.search(r"--port[\s=]+(lscd:\S+)", body)
        if re.match(r"lscctl\s", body) and via:
            if not wait_until(lambda: self.lscd_has_client(via.group(1), p.pid) or p.poll() is not None):
                raise RuntimeError("%s did not connect to lscd within %d s" % (body, DEADLINE_S))
        elif re.match(r"lscctl\s", body):
            if not wait_until(lambda: port_open_and_waiting(p.pid) or p.poll() is not None):
                raise RuntimeError("%s did not open its port within %d s" % (body, DEADLINE_S))
        if re.match(r"lscd\s", body):
            where = lscd_port_of(body)
            if not wait_until(lambda: self.lscd_status(where) is not None or p.poll() is not None):
                raise RuntimeError("%s did not answer on %s within %d s" % (body, where, DEADLINE_S))
            if p.poll() is not None:
                return (p.returncode,) + self.outputs(n)
        m = re.search(r"--link[\s=]+(\S+)", body)
        if m:
            path = os.path.join(self.cwd, m.group(1))
            if not wait_until(lambda: os.path.exists(path) or p.poll() is not None):
                raise RuntimeError("%s did not appear within %d s" % (path, DEADLINE_S))
            if p.poll() is not None:
                return (p.returncode,) + self.outputs(n)
        return 0, "", ""

    def lscd_status(self, port):
        """What `lscctl --port lscd:... status` prints, in the session's
        environment; None when lscd does not answer."""
        p = subprocess.run(["lscctl", "--port", port, "status"], cwd=self.cwd, env=self.env,
                           stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                           stderr=subprocess.DEVNULL, timeout=COMMAND_LIMIT_S)
        return decode(p.stdout) if p.returncode == 0 else None

    def lscd_has_client(self, port, pgid):
        """lscd lists a client whose process is in the process group pgid (it
        connected: notifications from now on reach it)."""
        for pid in re.findall(r"^client: .*\bpid=([0-9]+)", self.lscd_status(port) or "", re.M):
            try:
                if os.getpgid(int(pid)) == pgid:
                    return True
            except OSError:
                pass
        return False

    def outputs(self, n):
        """(stdout, stderr if apart) of job n so far."""
        _, out, err = self.jobs[n]
        return self.shown(read(out)), self.shown(read(err) if err else "")

    def job(self, which):
        n = max(self.jobs, default=0) if which in ("%", "+") else int(which)
        if n not in self.jobs:
            raise RuntimeError("no job %%%s" % which)
        return n

    def kill(self, which, want_lines, sig=None):
        """kill [-SIG] %N: see the rules at the top."""
        n = self.job(which)
        p, out, _ = self.jobs[n]
        if sig is not None:
            os.killpg(p.pid, sig)
            return 0, "", ""
        wait_until(lambda: read(out).count("\n") >= want_lines or p.poll() is not None)
        try:
            os.killpg(p.pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
        p.wait(timeout=DEADLINE_S)
        return (0,) + self.forget(n)

    def wait(self, which):
        n = self.job(which)
        status = self.jobs[n][0].wait(timeout=COMMAND_LIMIT_S)
        return (status,) + self.forget(n)

    def forget(self, n):
        """The outputs of job n, which ended."""
        outputs = self.outputs(n)
        del self.jobs[n]
        return outputs

    def close(self):
        for p, _, _ in self.jobs.values():
            try:
                os.killpg(p.pid, signal.SIGTERM)
            except ProcessLookupError:
                pass
            p.wait(timeout=DEADLINE_S)
        shutil.rmtree(self.dir, ignore_errors=True)


def lscd_port_of(body):
    """The lscd:... name of the socket an lscd command line serves: --socket
    PATH, --instance NAME, or the NAME of its --port (lscd(8))."""
    m = re.search(r"--socket[\s=]+(\S+)", body)
    if m:
        return "lscd:" + (m.group(1) if "/" in m.group(1) else "./" + m.group(1))
    m = re.search(r"--(instance|port)[\s=]+(\S+)", body)
    name = m.group(2) if m else ""
    if m and m.group(1) == "port":
        name = "hid-" + name[4:] if name.startswith("hid:") else name.rstrip("/").rsplit("/", 1)[-1]
    return "lscd:" + re.sub(r"[^A-Za-z0-9_.-]", "_", name)


def port_open_and_waiting(pgid):
    """A process of group pgid holds a flock (lscctl locks the port it opens,
    then discards its input) and is asleep (waiting for input)."""
    try:
        with open("/proc/locks") as f:
            pids = {int(l.split()[4]) for l in f if l.split()[1:2] == ["FLOCK"]}
    except OSError:
        return False
    for pid in pids:
        try:
            with open("/proc/%d/stat" % pid) as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == pgid and fields[0] == "S":
            return True
    return False


def decode(b):
    return b.decode("utf-8", "replace")


def read(f):
    f.flush()
    f.seek(0)
    return f.read().decode("utf-8", "replace")


def wait_until(cond):
    end = time.monotonic() + DEADLINE_S
    while not cond():
        if time.monotonic() > end:
            return False
        time.sleep(0.01)
    return True


def in_sections(name, examples, sections):
    """The examples under the headings sections, in that order (all of them
    when sections is empty); a heading that is not there or has no command is
    an error."""
    if not sections:
        return examples
    out = []
    for heading in sections:
        under = [ex for ex in examples if ex.heading == heading]
        if not under:
            raise ValueError("%s: no ```sh block under a heading %r" % (name, heading))
        if not any(ex.kind not in ("not run", "file") and commands_of(ex) for ex in under):
            raise ValueError("%s: %r has no command to run" % (name, heading))
        out += under
    return out


def check_document(path, name, session_args, sections=()):
    """Runs the examples of one document (of its sections, when given) in a
    Session(*session_args); returns the number of failures."""
    text = open(path, encoding="utf-8").read()
    examples = roff_examples(name, text) if re.search(r"\.[1-9]$", name) else markdown_examples(name, text)
    examples = in_sections(name, examples, sections)
    failures = 0
    counts = {"run": 0, "dry-run": 0, "not run": 0, "file": 0}
    session = Session(*session_args)
    try:
        for ex in examples:
            counts[ex.kind] += 1
            if ex.kind == "not run":
                print("%s: not run: %s" % (ex.where(), ex.why))
                continue
            if ex.kind == "file":
                session.write(ex.why, ex.lines)
                print("file %s: %s" % (ex.where(), ex.why))
                continue
            for line, cmd, want in commands_of(ex):
                body, comment = split_comment(cmd)
                m = re.fullmatch(r"kill (?:-(?:SIG)?([A-Z0-9]+) )?%(%|\+|[0-9]+)", body)
                w = re.fullmatch(r"wait %(%|\+|[0-9]+)", body)
                if m:
                    sig = m.group(1)
                    sig = None if sig is None else signal.Signals(int(sig)) if sig.isdigit() else signal.Signals["SIG" + sig]
                    status, got, errors = session.kill(m.group(2), len(want), sig)
                elif w:
                    status, got, errors = session.wait(w.group(1))
                else:
                    status, got, errors = session.run(cmd, ex.kind == "dry-run")
                want_status = wanted_status(comment)
                problems = []
                if status != want_status:
                    problems.append("exit %d, the document says %d" % (status, want_status))
                # --here: a command shown without output (a build) is not compared
                if ex.kind == "run" and (want or not session.here):
                    got_text = normalise(got).rstrip("\n")
                    want_text = normalise("\n".join(want)).rstrip("\n")
                    if got_text != want_text:
                        problems.append("output differs")
                if problems:
                    failures += 1
                    print("FAIL %s:%d: $ %s\n  %s" % (name, line, cmd, "; ".join(problems)))
                    print("  the document shows:\n%s" % indent("\n".join(want)))
                    print("  the command printed:\n%s" % indent(got))
                    if errors:
                        print("  and on stderr:\n%s" % indent(errors))
                else:
                    print("ok   %s:%d: $ %s" % (name, line, body))
    finally:
        session.close()
    print("%s: %d run, %d dry-run (needs hardware), %d not run; %d failures"
          % (name, counts["run"], counts["dry-run"], counts["not run"], failures))
    return failures


def indent(text):
    return "\n".join("    | " + l for l in text.rstrip("\n").split("\n"))


def main(argv):
    args, sections, here = [], [], False
    i = 1
    while i < len(argv):
        if argv[i] == "--section" and i + 1 < len(argv):
            sections.append(argv[i + 1])
            i += 1
        elif argv[i] == "--here":
            here = True
        elif argv[i].startswith("-"):
            print("docs.py: unknown option %s\n%s" % (argv[i], __doc__), file=sys.stderr)
            return 2
        else:
            args.append(argv[i])
        i += 1
    if (here and not args) or (not here and len(args) < 3):
        print(__doc__, file=sys.stderr)
        return 2
    if here:
        lscctl = lsc_sim = source = None
        docs = args
    else:
        lscctl, lsc_sim, source = args[:3]
        docs = args[3:] or ["README.md", "cli/lscctl.1", "cli/lsc-sim.1"] + sorted(
            os.path.join("docs", f) for f in os.listdir(os.path.join(source, "docs"))
            if f.endswith(".md"))
    failures = 0
    for d in docs:
        path = d if here or os.path.isabs(d) else os.path.join(source, d)
        name = d if here or not os.path.isabs(d) else os.path.basename(d)
        try:
            failures += check_document(path, name, (lscctl, lsc_sim, source, here), sections)
        except (OSError, ValueError, RuntimeError, subprocess.TimeoutExpired) as e:
            print("FAIL %s: %s" % (d, e))
            failures += 1
    print("docs: %d failures" % failures)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
