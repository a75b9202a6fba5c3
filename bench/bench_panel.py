#!/usr/bin/python3
"""lsc-panel's figures: a slider's input event to its servo_move frame on
lsc-sim's wire (p50, p95), the page's weight, and lsc-panel's CPU while idle
with a page open. lsc-sim runs paced at 9600 baud, lsc-panel on its pty
(and, with --lscd, through lscd), the page in headless Chromium.
Usage: /usr/bin/python3 bench/bench_panel.py [BUILD_DIR] [--samples N] [--lscd]
(BUILD_DIR: build/bench by default; needs chromium, chromium-driver and
python3-selenium)."""
import http.client
import os
import re
import statistics
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
sys.path.insert(0, os.path.join(root, "tests", "panel"))
from panel_lib import Rig, wait_for  # noqa: E402

args = [a for a in sys.argv[1:] if not a.startswith("--")]
build = os.path.abspath(args[0] if args else os.path.join(root, "build", "bench"))
samples = 100
if "--samples" in sys.argv:
    samples = int(sys.argv[sys.argv.index("--samples") + 1])
    build = os.path.abspath(args[0]) if len(args) > 1 else build
through_lscd = "--lscd" in sys.argv
os.environ.update(LSC_PANEL=build + "/cli/lsc-panel", LSC_SIM=build + "/cli/lsc-sim",
                  LSCD=build + "/cli/lscd", LSCCTL=build + "/cli/lscctl")

from selenium import webdriver  # noqa: E402
from selenium.webdriver.chrome.service import Service  # noqa: E402


def cpu_seconds(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main():
    rig = Rig()
    o = webdriver.ChromeOptions()
    o.binary_location = "/usr/bin/chromium"
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1100,1000"):
        o.add_argument(a)
    d = None
    try:
        port = rig.start_lscd() if through_lscd else rig.tty
        rig.start_panel(port, "--arm", os.path.join(root, "examples", "arms", "xarm.conf"))
        # the page's weight: what the browser fetches
        weight = 0
        for path in ("/", "/panel.css", "/panel.js"):
            c = http.client.HTTPConnection("127.0.0.1", rig.port)
            c.request("GET", path, headers={"Cookie": "lsc_panel_%d=%s" % (rig.port, rig.token)})
            weight += len(c.getresponse().read())
            c.close()
        d = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=o)
        d.get(rig.url)
        wait_for("the battery", lambda: "V" in d.find_element("id", "battery").text)
        d.execute_script("document.querySelector('input[name=time]').value = '0'")
        log = os.path.join(rig.tmp, "sim.log")
        lat = []
        frame = re.compile(rb" rx 55 55 08 03 01 .. .. 06 ")
        for i in range(samples):
            deg = 10 + i % 20
            size = os.path.getsize(log)
            t0 = d.execute_script(
                "const e = document.querySelector('input[name=base]'); e.value = arguments[0];"
                "const t = performance.timeOrigin + performance.now();"
                "e.dispatchEvent(new Event('input', {bubbles: true})); return t;", str(deg))
            seen = None
            deadline = time.monotonic() + 5
            while seen is None and time.monotonic() < deadline:
                with open(log, "rb") as f:
                    f.seek(size)
                    if frame.search(f.read()):  # each sample a new angle: a new frame
                        seen = time.time() * 1000
                if seen is None:
                    time.sleep(0.0005)
            if seen is None:
                raise AssertionError("no frame for sample %d" % i)
            lat.append(seen - t0)
            time.sleep(0.06)  # past the 40 ms limit: each input is sent on its own
        lat.sort()
        p50 = statistics.median(lat)
        p95 = lat[int(round(0.95 * (len(lat) - 1)))]
        # idle: the page open, nothing happening
        time.sleep(3)
        pid = rig.panel.pid
        c0, t0 = cpu_seconds(pid), time.monotonic()
        time.sleep(20)
        idle = (cpu_seconds(pid) - c0) / (time.monotonic() - t0) * 100
        mode = "through lscd" if through_lscd else "on lsc-sim's pty"
        print("lsc-panel %s (lsc-sim paced at 9600 baud), headless Chromium, %d samples:" %
              (mode, samples))
        print("  slider input -> servo_move on the wire: p50 %.1f ms, p95 %.1f ms, max %.1f ms"
              % (p50, p95, lat[-1]))
        print("  page weight: %d bytes (HTML, CSS and JavaScript, uncompressed)" % weight)
        print("  lsc-panel idle with the page open: %.2f %% of one core over 20 s" % idle)
    finally:
        if d is not None:
            d.quit()
        rig.close()


main()
