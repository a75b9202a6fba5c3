#!/usr/bin/python3
"""lsc-panel on a bus of servos: the bus inside the library (--port lx:sim),
lsc-sim --lx's on a pseudo-terminal (--port lx:PTY) and lscd serving lx:sim. Its configuration
says the kind; a move reaches the servos and reads back; what a bus has not
(action groups) is refused with the library's line; the battery, which a bus
has not, is said once (an event with mv null and why), not retried. GET
/api/servos lists the servos that answer with their position, temperature,
voltage and alarms (a whole bus, or ids=), and answers 404 on a board; the
page's "Servos on the bus" section shows them (in headless Chromium, when
chromium, chromedriver and python3-selenium are there) and is hidden on a
board. Environment: LSC_PANEL, LSC_SIM, LSCD, LSCCTL (panel_lib)."""
import http.client
import json
import os
import socket
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from panel_lib import Rig, scale, wait_for, check, report  # noqa: E402


def request(rig, method, path):
    c = http.client.HTTPConnection("127.0.0.1", rig.port, timeout=60 * scale())
    c.request(method, path, headers={"Host": "127.0.0.1:%d" % rig.port,
                                     "Cookie": "lsc_panel_%d=%s" % (rig.port, rig.token),
                                     "Origin": rig.base})
    r = c.getresponse()
    data = r.read()
    c.close()
    return r.status, json.loads(data) if data else None


def events(rig, until, seconds=10.0):
    """Reads the event stream until until(events) holds (a list of (type,
    data)), or fails after seconds (scaled); returns the events."""
    s = socket.create_connection(("127.0.0.1", rig.port), timeout=1)
    s.sendall(("GET /api/events HTTP/1.1\r\nHost: 127.0.0.1:%d\r\nCookie: lsc_panel_%d=%s\r\n"
               "Accept: text/event-stream\r\n\r\n" % (rig.port, rig.port, rig.token)).encode())
    got, text = [], ""
    deadline = time.monotonic() + seconds * scale()
    try:
        while not until(got):
            if time.monotonic() > deadline:
                raise AssertionError("events: timed out; got %r" % got)
            try:
                chunk = s.recv(65536)
            except socket.timeout:
                continue
            if not chunk:
                break
            text += chunk.decode(errors="replace")
            while "\n\n" in text:
                block, text = text.split("\n\n", 1)
                kind = data = None
                for line in block.split("\n"):
                    if line.startswith("event: "):
                        kind = line[7:]
                    elif line.startswith("data: "):
                        data = json.loads(line[6:])
                if kind:
                    got.append((kind, data))
    finally:
        s.close()
    return got


def moves_and_reads(rig, name, kind="lx"):
    status, cfg = request(rig, "GET", "/api/config")
    check("%s: the configuration says its kind, %s: %r" % (name, kind, cfg),
          status == 200 and cfg["kind"] == kind and cfg["groups"] == [])
    status, d = request(rig, "POST", "/api/move?time=0&s=2:700&s=3:250")
    check("%s: a move: 202, got %d %r" % (name, status, d), status == 202)
    pose = {}

    def there():
        nonlocal pose
        _, pose = request(rig, "POST", "/api/pose")
        return pose.get("pos", [])[1:3] == [700, 250]
    wait_for("%s: servos 2 and 3 at 700 and 250" % name, there)
    check("%s: the pose: %r" % (name, pose), pose["ids"][:3] == [1, 2, 3] and
          pose["pos"][:3] == [500, 700, 250])
    status, d = request(rig, "POST", "/api/run?group=1")
    check("%s: a group's run refused, the library's line: %d %r" % (name, status, d),
          status == 400 and "has no action groups; nothing was sent" in d["error"])
    status, d = request(rig, "POST", "/api/halt")
    check("%s: halt: %d %r" % (name, status, d), status == 200)


def servo_list(rig):
    """GET /api/servos on a bus of servos 1..3 and 9, servos 2 and 3 at 700 and 250."""
    status, d = request(rig, "GET", "/api/servos")
    servos = d["servos"] if status == 200 else []
    check("the whole bus: 254 ids asked, 1..3 and 9 found: %d %r" % (status, d),
          status == 200 and d["asked"] == 254 and [x["id"] for x in servos] == [1, 2, 3, 9])
    check("each with its readings: %r" % servos,
          all(x.get("temperature_c") == 30 and x.get("vin_mv") == 7500 and
              x.get("alarms") == 7 and x.get("mode") == "servo" for x in servos) and
          [x.get("position") for x in servos] == [500, 700, 250, 500])
    status, d = request(rig, "GET", "/api/servos?ids=2,4")
    check("ids=2,4: 2 found: %d %r" % (status, d), status == 200 and d["asked"] == 2 and
          [x["id"] for x in d["servos"]] == [2] and d["servos"][0]["torque"] is True)
    for bad in ("254", "x", "1-"):
        status, d = request(rig, "GET", "/api/servos?ids=" + bad)
        check("ids=%s refused: %d %r" % (bad, status, d), status == 400 and "ids=" in d["error"])


def halt_cuts_a_scan(rig):
    """Halt during a whole bus's scan (about 2 s) is answered at once and
    cuts the scan short: the servos do not wait for the scan to end. The
    halt may come before the scan began (then the scan runs whole): tried
    again until it lands inside one."""
    for attempt in range(10):
        got = {}
        t = threading.Thread(target=lambda: got.update(r=request(rig, "GET", "/api/servos")))
        t.start()
        time.sleep(0.3 * (attempt + 1))  # (not a synchronisation: retried when early)
        start = time.monotonic()
        status, d = request(rig, "POST", "/api/halt")
        took = time.monotonic() - start
        t.join()
        scan_status, scan = got["r"]
        if scan_status != 200:
            check("a halt during a scan: answered in %.3f s, %d %r; the scan %d %r" %
                  (took, status, d, scan_status, scan),
                  status == 200 and took < 1.0 * scale() and
                  "Halt: the command was cut short" in scan.get("error", ""))
            print("a halt during a whole bus's scan was answered in %.3f s" % took)
            return
    check("a halt landed inside a scan in 10 tries (each scan ran whole)", False)


def page(rig, bus):
    """The page's section of a bus's servos: shown and filled on a bus,
    hidden on a board. False when no browser is here."""
    try:
        from selenium.webdriver.common.by import By
        from panel_lib import browser
    except ImportError:
        return False
    if not (os.access("/usr/bin/chromium", os.X_OK) and os.access("/usr/bin/chromedriver", os.X_OK)):
        return False
    d = browser()
    try:
        d.get(rig.url)
        wait_for("the page's configuration", lambda: "(" in d.find_element(By.ID, "device").text)
        shown = d.find_element(By.ID, "bus").is_displayed()
        check("the bus's section %s: %r" % ("shown" if bus else "hidden", shown), shown == bus)
        if bus:
            wait_for("the battery said", lambda: d.find_element(By.ID, "battery").text == "none")
            d.find_element(By.CSS_SELECTOR, "button[data-action=scan]").click()
            rows = lambda: d.find_elements(By.CSS_SELECTOR, "#bus-servos tbody tr")  # noqa: E731
            wait_for("the scan's rows", lambda: len(rows()) == 4, 30)
            cells = [c.text for c in rows()[1].find_elements(By.CSS_SELECTOR, "th, td")]
            check("servo 2's row: %r" % cells,
                  cells == ["2", "700", "30 °C", "7.50 V", "temperature, voltage, stall"])
            check("the count: %r" % d.find_element(By.ID, "bus-count").text,
                  d.find_element(By.ID, "bus-count").text == "4 servos of 254 ids asked")
        logs = [e for e in d.get_log("browser") if e["level"] == "SEVERE"]
        check("the browser logs no error: %r" % logs, logs == [])
    finally:
        d.quit()
    return True


def main():
    rig = Rig()
    try:
        rig.start_panel("lx:sim:1-3,9", "--ids", "1-3")
        moves_and_reads(rig, "lx:sim")
        servo_list(rig)
        halt_cuts_a_scan(rig)
        if not page(rig, True):
            print("the page's section not checked: no chromium, chromedriver or python3-selenium")
        got = events(rig, lambda ev: any(k == "battery" for k, _ in ev) and
                     any(k == "positions" for k, _ in ev))
        battery = [d for k, d in got if k == "battery"]
        check("lx:sim: the battery said once, with why: %r" % got,
              len(battery) == 1 and battery[0]["mv"] is None and
              "a bus has no battery reading" in battery[0]["why"] and
              not any(k == "error" for k, _ in got))
        pos = [d for k, d in got if k == "positions"][-1]
        check("lx:sim: positions: %r" % pos, pos["pos"][:3] == [500, 700, 250])
        # a page that comes later gets the battery's last word too
        got = events(rig, lambda ev: any(k == "battery" for k, _ in ev))
        check("lx:sim: the battery's last word for a later page: %r" % got,
              [d["mv"] for k, d in got if k == "battery"] == [None])
    finally:
        codes = rig.close()
        check("exit 0 on SIGTERM: %r" % codes, codes == [0, 0])

    # through lscd serving lx:sim: moves and reads; no servos' list (404)
    rig = Rig()
    try:
        run = os.path.join(rig.tmp, "run")
        os.makedirs(run)
        env = dict(os.environ, LSC_LSCD_DIR=run)
        rig.start([os.environ["LSCD"], "--port", "lx:sim"], env=env,
                  stderr=open(os.path.join(rig.tmp, "lscd.log"), "w"))
        sock = os.path.join(run, "lx-sim.sock")
        wait_for("lscd on lx:sim", lambda: rig.lscctl("--port", "lscd:" + sock, "status",
                                                      check=False).returncode == 0)
        rig.start_panel("lscd:" + sock)
        moves_and_reads(rig, "lscd:lx-sim", "lscd")
        got = events(rig, lambda ev: any(k == "battery" for k, _ in ev))
        check("through lscd: the battery said once, with why: %r" % got,
              [d["mv"] for k, d in got if k == "battery"] == [None] and
              "a bus has no battery reading" in [d for k, d in got if k == "battery"][0]["why"])
        status, d = request(rig, "GET", "/api/servos")
        check("through lscd: 404 with why: %d %r" % (status, d), status == 404 and
              "is no bus of servos opened directly" in d["error"])
    finally:
        codes = rig.close()
        check("exit 0 on SIGTERM: %r" % codes, codes == [0, 0, 0])

    # a board: no servos' list, the section hidden
    rig = Rig()
    try:
        rig.start_panel(rig.tty)
        status, d = request(rig, "GET", "/api/servos")
        check("a board: 404 with why: %d %r" % (status, d), status == 404 and
              "is no bus of servos" in d["error"])
        page(rig, False)
    finally:
        codes = rig.close()
        check("exit 0 on SIGTERM: %r" % codes, codes == [0, 0])

    rig = Rig(sim_args=("--lx", "1-3"))
    try:
        rig.start_panel("lx:" + rig.tty, "--ids", "1-3")
        moves_and_reads(rig, "lx:PTY")
    finally:
        codes = rig.close()
        check("exit 0 on SIGTERM: %r" % codes, codes == [0, 0])

    return report()


if __name__ == "__main__":
    sys.exit(main())
