#!/usr/bin/python3
"""lsc-panel's refusals, without a browser: the token, the Host header, the
Origin of state changes, file names, sizes, bad arguments; each gets a clear
4xx and changes nothing (no frame reaches lsc-sim, no file is written). And
its command line: the printed address, bad options.
Environment: LSC_PANEL, LSC_SIM, LSCD, LSCCTL."""
import http.client
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from panel_lib import Rig, scale, check, report  # noqa: E402



def request(rig, method, path, host=None, cookie=True, origin=None, body=None, headers=None):
    c = http.client.HTTPConnection("127.0.0.1", rig.port, timeout=30 * scale())
    h = {"Host": host or "127.0.0.1:%d" % rig.port}
    if cookie:
        h["Cookie"] = "lsc_panel_%d=%s" % (rig.port, cookie if isinstance(cookie, str) else rig.token)
    if origin:
        h["Origin"] = origin
    h.update(headers or {})
    c.request(method, path, body=body, headers=h)
    r = c.getresponse()
    data = r.read()
    c.close()
    return r, data


def refused(rig, status, method, path, **kw):
    r, data = request(rig, method, path, **kw)
    msg = ""
    try:
        msg = json.loads(data)["error"]
    except (ValueError, KeyError, TypeError):
        pass
    check("%s %s %r -> %d %r, want %d with a message" % (method, path, kw, r.status, data, status),
          r.status == status and msg != "")
    return msg


def verify_unit():
    """lsc-panel@.service passes systemd-analyze verify beside lscd's units
    (the programs as built), and runs lsc-panel on lscd:%i."""
    import shutil
    import tempfile
    if not shutil.which("systemd-analyze") or not os.environ.get("PANEL_UNITS"):
        print("systemd-analyze is not installed (package systemd): the unit was not verified")
        return
    with tempfile.TemporaryDirectory() as t:
        for src, prog, name in (
                (os.environ["PANEL_UNITS"] + "/lsc-panel@.service", os.environ["LSC_PANEL"],
                 "lsc-panel@ttyUSB0.service"),
                (os.environ["LSCD_UNITS"] + "/lscd@.service", os.environ["LSCD"],
                 "lscd@ttyUSB0.service"),
                (os.environ["LSCD_UNITS"] + "/lscd@.socket", os.environ["LSCD"],
                 "lscd@ttyUSB0.socket")):
            with open(src) as f:
                text = f.read()
            if name.startswith("lsc-panel"):
                check("the unit runs lsc-panel on lscd:%i", "/lsc-panel --port lscd:%i " in text)
            lines = [("ExecStart=" + prog + " " + line.split(" ", 1)[1])
                     if line.startswith("ExecStart=") else line for line in text.split("\n")]
            with open(os.path.join(t, name), "w") as f:
                f.write("\n".join(lines))
        r = subprocess.run(["systemd-analyze", "verify", "--man=no", "lsc-panel@ttyUSB0.service",
                            "lscd@ttyUSB0.socket", "lscd@ttyUSB0.service"], cwd=t,
                           capture_output=True, text=True, env=dict(os.environ,
                                                                    SYSTEMD_LOG_LEVEL="notice"))
        check("systemd-analyze verify: %d %s%s" % (r.returncode, r.stdout, r.stderr),
              r.returncode == 0 and r.stdout + r.stderr == "")


def main():
    # the command line
    p = os.environ["LSC_PANEL"]
    for args, code in ((["--listen", "nowhere"], 2), (["--listen", "example.com:80"], 2),
                       (["--dir", "/nonexistent/dir"], 2), (["--bogus"], 2),
                       (["--timeout", "0"], 2), (["--ids", "1-"], 2),
                       (["--arm", "/nonexistent.conf"], 1 if False else 2)):
        r = subprocess.run([p, "--port", "sim", *args], capture_output=True, text=True,
                           stdin=subprocess.DEVNULL, timeout=30 * scale())
        check("lsc-panel %s -> exit %d, stderr %r; want %d and one line" %
              (args, r.returncode, r.stderr, code),
              r.returncode == code and r.stderr.count("\n") == 1 and r.stdout == "")
    r = subprocess.run([p, "--port", "/nonexistent/tty"], capture_output=True, text=True,
                       stdin=subprocess.DEVNULL, timeout=30 * scale())
    check("a port that is not there: exit 1 and one line, got %d %r" % (r.returncode, r.stderr),
          r.returncode == 1 and r.stderr.count("\n") == 1)

    verify_unit()
    rig = Rig()
    try:
        rig.start_panel(rig.tty, "--arm", os.environ["ARM"])
        me = rig.base
        r = subprocess.run([p, "--port", "sim", "--listen", "127.0.0.1:%d" % rig.port],
                           capture_output=True, text=True, stdin=subprocess.DEVNULL,
                           timeout=30 * scale())
        check("a port in use: exit 1 and one line, got %d %r" % (r.returncode, r.stderr),
              r.returncode == 1 and r.stderr.count("\n") == 1 and "Address already in use"
              in r.stderr)
        # the printed address sets the cookie and drops the token from the address
        r, _ = request(rig, "GET", "/?token=" + rig.token, cookie=False)
        cookie = r.getheader("Set-Cookie") or ""
        check("sign-in: 303 to / with an HttpOnly SameSite=Strict cookie, got %d %r" %
              (r.status, cookie), r.status == 303 and r.getheader("Location") == "/" and
              "HttpOnly" in cookie and "SameSite=Strict" in cookie and rig.token in cookie)
        r, data = request(rig, "GET", "/")
        check("the page with the cookie: %d %r" % (r.status, data[:200]),
              r.status == 200 and b"<html" in data)
        check("the page's policy loads nothing from elsewhere",
              "default-src 'self'" in (r.getheader("Content-Security-Policy") or ""))
        r, _ = request(rig, "GET", "/favicon.ico", cookie=False)
        check("favicon: 204, got %d" % r.status, r.status == 204)
        r, data = request(rig, "GET", "/api/config", host="localhost:%d" % rig.port)
        check("Host localhost:PORT on a loopback address is this server", r.status == 200)

        # the token
        refused(rig, 403, "GET", "/", cookie=False)
        refused(rig, 403, "GET", "/api/config", cookie=False)
        refused(rig, 403, "GET", "/api/config", cookie="0" * 32)
        # the cookie of a panel on another port (cookies are not kept apart by port)
        r, _ = request(rig, "GET", "/api/config", cookie=False,
                       headers={"Cookie": "lsc_panel_%d=%s" % (rig.port + 1, rig.token)})
        check("another port's cookie: 403, got %d" % r.status, r.status == 403)
        check("the sign-in names the cookie by port: %r" % cookie,
              cookie.startswith("lsc_panel_%d=" % rig.port))
        refused(rig, 403, "GET", "/?token=" + "0" * 32, cookie=False)
        refused(rig, 403, "POST", "/api/run?group=1", cookie=False, origin=me)
        # DNS rebinding: a Host that is not this server's address
        for host in ("evil.example:%d" % rig.port, "127.0.0.1:1", "127.0.0.1",
                     "localhost.evil.example:%d" % rig.port, "[::1]:%d" % rig.port):
            refused(rig, 421, "GET", "/api/config", host=host)
            refused(rig, 421, "GET", "/?token=" + rig.token, host=host, cookie=False)
        refused(rig, 421, "POST", "/api/run?group=1", host="evil.example:%d" % rig.port,
                origin="http://evil.example:%d" % rig.port)
        # state changes need the page's own Origin
        refused(rig, 403, "POST", "/api/run?group=1")
        refused(rig, 403, "POST", "/api/run?group=1", origin="http://evil.example")
        refused(rig, 403, "POST", "/api/move?s=base:10deg", origin="null")
        # methods, paths, arguments
        refused(rig, 405, "GET", "/api/run?group=1")
        refused(rig, 405, "POST", "/api/config", origin=me)
        refused(rig, 404, "GET", "/etc/passwd")
        refused(rig, 404, "GET", "/../panel.js")
        refused(rig, 400, "POST", "/api/run?group=300", origin=me)
        refused(rig, 400, "POST", "/api/run", origin=me)
        refused(rig, 400, "POST", "/api/speed?group=1&percent=0", origin=me)
        refused(rig, 400, "POST", "/api/move?s=base:200deg", origin=me)
        refused(rig, 400, "POST", "/api/move?s=nojoint:10deg", origin=me)
        refused(rig, 400, "POST", "/api/move?s=base:10deg&s=6:500", origin=me)
        refused(rig, 400, "POST", "/api/move?time=70000&s=base:10deg", origin=me)
        refused(rig, 400, "POST", "/api/move", origin=me)
        m = refused(rig, 400, "POST", "/api/move?s=elbow:150deg", origin=me)
        check("a move outside the limits names the joint: %r" % m, "elbow" in m)
        # jogs: an axis, a step (signed, not 0, bounded), a time
        r, data = request(rig, "GET", "/api/config")
        check("the profile states its geometry: %r" % data, json.loads(data)["geometry"] is True)
        for q in ("", "?step=10", "?axis=w&step=10", "?axis=Z&step=10", "?axis=z",
                  "?axis=z&step=", "?axis=z&step=0", "?axis=z&step=-0.0", "?axis=z&step=abc",
                  "?axis=z&step=1e3", "?axis=z&step=1001", "?axis=z&step=-1001",
                  "?axis=z&step=--5", "?axis=z&step=5-", "?axis=z&step=1.2.3", "?axis=z&step=.",
                  "?axis=z&step=%2B", "?axis=z&step=nan", "?axis=z&step=inf",
                  "?axis=z&step=%205", "?axis=z&step=0000000000001",
                  "?axis=pitch&step=181", "?axis=z&step=10&time=70000",
                  "?axis=z&step=10&time=-1"):
            m = refused(rig, 400, "POST", "/api/jog" + q, origin=me)
        check("a bad step says what a step is: %r" % m, "time=" in m)
        m = refused(rig, 400, "POST", "/api/jog?axis=z&step=1e3", origin=me)
        check("a bad step says what a step is: %r" % m, "step=" in m and "mm" in m)
        m = refused(rig, 400, "POST", "/api/jog?axis=pitch&step=200", origin=me)
        check("a bad pitch step says degrees: %r" % m, "degrees" in m)
        refused(rig, 405, "GET", "/api/jog?axis=z&step=10")
        refused(rig, 403, "POST", "/api/jog?axis=z&step=10")
        refused(rig, 403, "POST", "/api/jog?axis=z&step=10", cookie=False, origin=me)
        # files: names in --dir only, known formats, sane bodies
        good = "time_ms,1,2,3,4,5,6\n1000,500,500,500,500,500,500\n"
        for name in ("../x.rob", ".x.rob", "a%2Fb.csv", "x.h", "x", "", "x.rob%00.csv",
                     "%2Fetc%2Fx.csv", "a" * 70 + ".csv", "x%20y.csv", "x.journal.cs"):
            refused(rig, 400, "POST", "/api/save?name=" + name, origin=me, body=good)
            refused(rig, 400, "GET", "/api/file?name=" + name)
        refused(rig, 400, "POST", "/api/save?name=x.csv", origin=me, body="not,csv\nat all")
        refused(rig, 400, "POST", "/api/save?name=x.rob", origin=me,
                body="time_ms,1,2,3,4,5,6\n1000,1500,500,500,500,500,500\n")
        refused(rig, 400, "POST", "/api/play", origin=me, body="time_ms,1\n")
        refused(rig, 413, "POST", "/api/save?name=x.csv", origin=me, body=good,
                headers={"Content-Length": str(16 * 1024 * 1024 + 1)})
        refused(rig, 400, "POST", "/api/run?group=1", origin=me, body="x")
        # a body of a few MB is not too large (16 MiB is): the parser refuses it
        refused(rig, 400, "POST", "/api/save?name=big.csv", origin=me,
                body="x" * (3 * 1024 * 1024))
        # a link in --dir is not the panel's file, even to a file it could read
        outside = os.path.join(os.path.dirname(rig.files), "outside.csv")
        with open(outside, "w") as f:
            f.write(good)
        os.symlink(outside, os.path.join(rig.files, "link.csv"))
        refused(rig, 400, "GET", "/api/file?name=link.csv")
        refused(rig, 400, "POST", "/api/save?name=link.csv", origin=me, body=good)
        r, data = request(rig, "GET", "/api/files")
        check("a link is not listed: %r" % data, json.loads(data)["files"] == [])
        os.unlink(os.path.join(rig.files, "link.csv"))
        refused(rig, 404, "GET", "/api/file?name=missing.csv")
        check("nothing was written in --dir: %r" % os.listdir(rig.files),
              os.listdir(rig.files) == [])
        check("no frame reached lsc-sim: %r" % rig.log("sim"), " rx " not in rig.log("sim"))

        # what is allowed works
        r, _ = request(rig, "POST", "/api/save?name=ok.csv", origin=me, body=good)
        check("save ok.csv: %d" % r.status, r.status == 200 and os.listdir(rig.files) == ["ok.csv"])
        r, data = request(rig, "GET", "/api/files")
        check("files lists ok.csv: %r" % data, json.loads(data)["files"] ==
              [{"name": "ok.csv", "bytes": os.path.getsize(os.path.join(rig.files, "ok.csv"))}])
        r, data = request(rig, "GET", "/api/file?name=ok.csv")
        check("open ok.csv: %r" % data, r.status == 200 and data.decode() == good)
        r, _ = request(rig, "POST", "/api/move?time=100&s=base:30deg", origin=me)
        check("a move: 202, got %d" % r.status, r.status == 202)
        from panel_lib import wait_for
        wait_for("servo 6 to 625", lambda: {6: 625} in rig.moves())
        # a group Stop during a play (a minute long) stops the play too, at once
        slow = "time_ms,1,2,3,4,5,6\n" + "30000,500,500,500,500,500,500\n" * 2
        r, _ = request(rig, "POST", "/api/play?speed=100", origin=me, body=slow)
        check("a long play starts: %d" % r.status, r.status == 200)
        r, _ = request(rig, "POST", "/api/run?group=1", origin=me)
        check("while it plays a run is refused: %d" % r.status, r.status == 409)
        r, _ = request(rig, "POST", "/api/stop", origin=me)
        check("Stop during the play: %d" % r.status, r.status == 200)
        r, _ = request(rig, "POST", "/api/run?group=1", origin=me)
        check("after Stop the play is over: a run goes, got %d" % r.status, r.status == 200)
    finally:
        codes = rig.close()
        check("lsc-panel and lsc-sim exit 0 on SIGTERM: %r" % codes, codes == [0, 0])
    # without --arm: servo ids and positions
    rig = Rig()
    try:
        rig.start_panel(rig.tty, "--ids", "1-3")
        me = rig.base
        r, data = request(rig, "GET", "/api/config")
        joints = json.loads(data)["joints"]
        check("--ids 1-3: joints 1..3 in positions: %r" % joints,
              [(j["name"], j["id"], j["unit"], j["min"], j["max"]) for j in joints] ==
              [("1", 1, "pos", 0, 1000), ("2", 2, "pos", 0, 1000), ("3", 3, "pos", 0, 1000)])
        refused(rig, 400, "POST", "/api/move?s=base:10deg", origin=me)
        r, _ = request(rig, "POST", "/api/move?time=0&s=3:700&s=1:250", origin=me)
        check("a move by ids: 202, got %d" % r.status, r.status == 202)
        from panel_lib import wait_for
        wait_for("servos 3 and 1 to 700 and 250", lambda: {3: 700, 1: 250} in rig.moves())
        r, data = request(rig, "POST", "/api/pose", origin=me)
        check("take a pose: %r" % data, r.status == 200 and
              json.loads(data) == {"ids": [1, 2, 3], "pos": [250, 1500, 700],
                                   "deg": [None, None, None]})
        r, data = request(rig, "GET", "/api/config")
        check("no profile, no geometry: %r" % data, json.loads(data)["geometry"] is False)
        since = len(rig.log("sim"))
        m = refused(rig, 409, "POST", "/api/jog?axis=z&step=10", origin=me)
        check("a jog without a profile says so: %r" % m, "--arm" in m)
        check("the jog sent nothing", " rx " not in rig.log("sim")[since:])
    finally:
        codes = rig.close()
        check("exit 0 on SIGTERM: %r" % codes, codes == [0, 0])
    # a profile without geometry (no chain: and links: lines)
    rig = Rig()
    try:
        prof = os.path.join(rig.tmp, "nogeometry.conf")
        with open(os.environ["ARM"]) as f, open(prof, "w") as out:
            out.write("".join(line for line in f if not line.startswith(("chain:", "links:"))))
        rig.start_panel(rig.tty, "--arm", prof)
        r, data = request(rig, "GET", "/api/config")
        check("a profile without geometry: %r" % data, json.loads(data)["geometry"] is False)
        m = refused(rig, 409, "POST", "/api/jog?axis=x&step=-10", origin=rig.base)
        check("a jog without geometry names the lines: %r" % m, "chain:" in m)
        check("no frame reached lsc-sim: %r" % rig.log("sim"), " rx " not in rig.log("sim"))
    finally:
        codes = rig.close()
        check("exit 0 on SIGTERM: %r" % codes, codes == [0, 0])
    return report()


sys.exit(main())
