#!/usr/bin/python3
"""lsc-panel in headless Chromium against lsc-sim, directly (the pty) and
through lscd: the battery, a slider sends its servo, notifications (through
lscd: from another program) appear in #events, three poses taken and saved
as bar.rob read back with lscctl convert, play sends them, limp and hold,
keyboard use, a 375-pixel-wide screen; the browser logs no error and fetches
nothing outside the server. Saves a screenshot (SCREENSHOT, if set).
Skipped (77) without chromium, chromedriver or python3-selenium.
Environment: LSC_PANEL, LSC_SIM, LSCD, LSCCTL, ARM, SIM_GROUPS, SCREENSHOT."""
import csv
import json
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from panel_lib import Rig, browser, scale, skip, wait_for  # noqa: E402

CHROMIUM, DRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
if not (os.access(CHROMIUM, os.X_OK) and os.access(DRIVER, os.X_OK)):
    skip("chromium and chromium-driver are not installed (apt-get install chromium "
         "chromium-driver python3-selenium)")
try:
    import selenium.webdriver  # noqa: F401 (panel_lib.browser's)
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys
except ImportError:
    skip("python3-selenium is not installed (run with Debian's /usr/bin/python3)")


def scenario(d, rig, through_lscd, screenshot):
    def one(css):
        # in the middle of the window: never under the page's sticky header
        e = d.find_element(By.CSS_SELECTOR, css)
        d.execute_script("arguments[0].scrollIntoView({block: 'center'})", e)
        return e
    every = lambda css: d.find_elements(By.CSS_SELECTOR, css)  # noqa: E731
    wait = lambda what, cond, s=15: wait_for(what, lambda: _try(cond), s)  # noqa: E731

    def slide(name, value):
        d.execute_script("const e = document.querySelector(arguments[0]); e.value = arguments[1];"
                         "e.dispatchEvent(new Event('input', {bubbles: true}));"
                         "e.dispatchEvent(new Event('change', {bubbles: true}));",
                         'input[name="%s"]' % name, str(value))

    def readback(name):
        return one('output[data-joint="%s"]' % name).text

    d.get(rig.url)
    wait("the page without the token in its address", lambda: d.current_url == rig.base + "/")
    wait("7.5 in #battery", lambda: "7.5" in one("#battery").text)
    assert one("#battery").text == "7.5 V", one("#battery").text
    names = [e.get_attribute("name") for e in every("#joints input[type=range]")]
    assert names == ["gripper", "wrist-rotate", "wrist", "elbow", "shoulder", "base"], names
    d.execute_script("document.querySelector('input[name=time]').value = '100'")

    # every joint to 0 degrees (position 500), one move
    for n in names:
        slide(n, 0)
    wait("every joint read back at 0", lambda: all(readback(n).startswith("0.00")
                                                   for n in names))
    # the Done-when: base to 30 degrees sends servo 6 to 625
    slide("base", 30)
    wait("servo 6 sent to 625", lambda: {6: 625} in rig.moves())
    wait("base read back at 30", lambda: readback("base") == "30.00° (625)")

    # dragging: many inputs, at most one move per 40 ms, the last value wins
    before = len(rig.moves())
    t0 = d.execute_script("const e = document.querySelector('input[name=wrist]');"
                          "const t = performance.now();"
                          "for (let v = 1; v <= 20; v++) { e.value = v;"
                          "  e.dispatchEvent(new Event('input', {bubbles: true})); }"
                          "return t;")
    assert t0 >= 0
    wait("the last value sent", lambda: rig.moves()[-1].get(3) == 500 + round(20 / 0.24))
    sent = rig.moves()[before:]
    assert 1 <= len(sent) <= 2, sent  # the first at once, then the latest

    # keyboard: a slider moves with the arrow keys
    one("input[name=base]").send_keys(Keys.ARROW_LEFT)
    wait("base 29 degrees by keyboard", lambda: {6: 621} in rig.moves())

    hand(d, rig, through_lscd, one, slide, readback, wait)

    # notifications: through lscd from another program, directly from the page
    if through_lscd:
        rig.lscctl("--port", "lscd:" + rig.sock, "run", "1")
    else:
        one("input[name=group]").clear()
        one("input[name=group]").send_keys("1")
        one('button[data-action="run"]').click()
    wait("#events [data-kind=run][data-group=\"1\"]",
         lambda: every('#events [data-kind=run][data-group="1"]'))
    wait("group 1 completes", lambda: every('#events [data-kind=complete][data-group="1"]'))
    # a group the controller does not have: said never to have started
    one("input[name=group]").clear()
    one("input[name=group]").send_keys("9")
    one('button[data-action="run"]').click()
    wait("group 9 never started", lambda: "never started" in one(
        '#events [data-kind="never-started"][data-group="9"]').text)
    wait("... in #status too", lambda: "group 9 never started" in one("#status").text)

    # teach: three poses with different elbow angles
    for i, elbow in enumerate((-30, 0, 30)):
        for n in names:
            slide(n, 30 if n == "base" else 0)
        slide("elbow", elbow)
        wait("elbow at %d" % elbow, lambda: readback("elbow").startswith("%d.00°" % elbow) and
             readback("gripper").startswith("0.00") and readback("wrist").startswith("0.00"))
        one('button[data-action="take-pose"]').click()
        wait("keyframe %d" % (i + 1), lambda: len(every("[data-keyframe]")) == i + 1)
    # edit a time, reorder there and back (by keyboard), delete a fourth
    t2 = one('[data-keyframe="2"] input[name=keyframe-time]')
    t2.clear()
    t2.send_keys("500" + Keys.TAB)
    one('[data-keyframe="1"] [data-action=down]').send_keys(Keys.ENTER)
    wait("keyframe 1 moved down", lambda: "elbow -30.0°" in one('[data-keyframe="2"]').text)
    focused = d.switch_to.active_element
    assert focused.get_attribute("data-action") == "down", "the focus follows the keyframe"
    one('[data-keyframe="2"] [data-action=up]').send_keys(Keys.ENTER)
    wait("keyframe 1 is elbow -30", lambda: "elbow -30.0°" in one('[data-keyframe="1"]').text)
    one('button[data-action="take-pose"]').click()
    wait("keyframe 4", lambda: len(every("[data-keyframe]")) == 4)
    one('[data-keyframe="4"] [data-action=delete]').click()
    wait("three keyframes", lambda: len(every("[data-keyframe]")) == 3)
    elbows = [e.text for e in every("[data-keyframe] .pos")]
    # the teach list speaks joints and degrees
    assert ["elbow -30.0°" in elbows[0], "elbow 0.0°" in elbows[1],
            "elbow 30.0°" in elbows[2]] == [True] * 3, elbows
    assert "base 30.0°" in elbows[0] and ":" not in elbows[0], elbows
    assert one("#kf-count").text == "3 keyframes", one("#kf-count").text

    # save as bar.rob; lscctl convert reads it back
    one("input[name=file]").clear()
    one("input[name=file]").send_keys("bar.rob")
    one('button[data-action="save"]').click()
    wait("bar.rob listed", lambda: every('#files button[data-file="bar.rob"]'))
    out = os.path.join(rig.tmp, "bar%d.csv" % through_lscd)
    rig.lscctl("convert", os.path.join(rig.files, "bar.rob"), out)
    with open(out) as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["time_ms", "1", "2", "3", "4", "5", "6"], rows
    assert [r[4] for r in rows[1:]] == ["375", "500", "625"], rows
    assert [r[6] for r in rows[1:]] == ["625"] * 3, rows
    assert rows[2][0] == "500", rows

    # play sends them, in order, with progress
    since = len(rig.log("sim"))
    one('input[name="play-speed"]').clear()
    one('input[name="play-speed"]').send_keys("400")
    one('button[data-action="play"]').click()
    wait("play done", lambda: one("#status").text == "play done", 30)
    elbow = [m[4] for m in rig.moves(since) if 4 in m]
    assert elbow == [375, 500, 625], rig.moves(since)
    assert one("#progress").get_attribute("value") == "3", one("#progress").get_attribute("value")

    # a slow play, stopped
    one('input[name="play-speed"]').clear()
    one('input[name="play-speed"]').send_keys("10")
    one('button[data-action="play"]').click()
    wait("playing", lambda: one("#status").text == "playing")
    one('button[data-action="play-stop"]').click()
    wait("play stopped", lambda: one("#status").text.startswith("play stopped at keyframe"), 30)

    # open the file again
    d.execute_script("document.getElementById('keyframes').textContent = ''")
    one('#files button[data-file="bar.rob"]').click()
    wait("bar.rob opened", lambda: len(every("[data-keyframe]")) == 3)
    assert "elbow 30.0°" in one('[data-keyframe="3"] .pos').text, one('[data-keyframe="3"]').text

    # Halt: the button, and Esc wherever the focus is
    since = len(rig.log("sim"))
    one('button#halt').click()
    wait("halted", lambda: one("#status").text.startswith("halted"))
    wait("a group stop sent by Halt", lambda: " rx 55 55 02 07" in rig.log("sim")[since:])
    since = len(rig.log("sim"))
    one("input[name=file]").send_keys(Keys.ESCAPE)
    wait("a group stop sent by Esc", lambda: " rx 55 55 02 07" in rig.log("sim")[since:])

    # limp and hold
    since = len(rig.log("sim"))
    one('button[data-action="limp"]').click()
    wait("an unload frame", lambda: " 14 06 01 02 03 04 05 06" in rig.log("sim")[since:])
    one('button[data-action="hold"]').click()
    wait("a hold (a move to where they are)", lambda: rig.moves(since))

    # a phone's screen: nothing wider than 375 pixels; Take pose in view with
    # the sliders; Halt in view wherever the page is scrolled
    d.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                      {"width": 375, "height": 740, "deviceScaleFactor": 1, "mobile": True})
    wide = d.execute_script("return document.documentElement.scrollWidth")
    assert wide <= 375, "the page is %d pixels wide on a 375-pixel screen" % wide
    seen = d.execute_script("""
        const inView = (e) => { const r = e.getBoundingClientRect();
          return r.width > 0 && r.top >= 0 && r.bottom <= innerHeight; };
        const sliders = [...document.querySelectorAll('#joints input[type=range]')];
        sliders[sliders.length - 1].scrollIntoView({block: 'end'});
        const pose = document.querySelector('button[data-action="take-pose"]');
        const out = {pose: inView(pose), first: inView(sliders[0]),
                     last: inView(sliders[sliders.length - 1])};
        window.scrollTo(0, document.documentElement.scrollHeight);
        out.halt = inView(document.getElementById('halt'));
        out.scrolled = scrollY > 0;
        return out;""")
    assert seen == {"pose": True, "first": True, "last": True, "halt": True, "scrolled": True}, \
        seen
    d.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})

    if screenshot:  # the whole page, every section (docs/panel.png)
        d.set_window_size(1400, 1000)
        d.execute_script("window.scrollTo(0, 0)")
        inner, full = d.execute_script(
            "return [window.innerHeight, document.documentElement.scrollHeight]")
        d.set_window_size(1400, 1000 + full - inner)
        text = d.execute_script("return document.body.innerText")
        assert "/tmp" not in text and "lsc-panel-test" not in text, text
        d.save_screenshot(screenshot)

    if through_lscd:  # lscd goes away and comes back: the page says so meanwhile
        rig.stop_lscd()
        wait("#link says reconnecting", lambda: one("#link").is_displayed() and
             "Reconnecting" in one("#link").text)
        rig.restart_lscd()
        wait("#link hidden again", lambda: not one("#link").is_displayed(), 20)
        since = len(rig.log("sim"))
        slide("base", 10)
        wait("a move after lscd is back", lambda: rig.moves(since))

    # the browser: no error (but the refused jog's answer), nothing fetched from elsewhere
    errors = [e for e in d.get_log("browser") if e["level"] == "SEVERE" and not (
        "/api/jog?axis=z&step=1000&" in e["message"] and "status of 400" in e["message"])]
    assert not errors, errors
    urls = [json.loads(e["message"])["message"]["params"]["request"]["url"]
            for e in d.get_log("performance")
            if json.loads(e["message"])["message"]["method"] == "Network.requestWillBeSent"]
    outside = [u for u in urls if not (u.startswith(rig.base + "/") or u.startswith("data:"))]
    assert urls and not outside, outside


def hand(d, rig, through_lscd, one, slide, readback, wait):
    """The grasp point shown (#where) is lscctl where's (through lscd: the
    pty is the panel's alone) within 1 mm; a jog z+ by keyboard moves it up
    by the step; an unreachable jog says the library's why and sends
    nothing."""
    assert one("#hand").is_displayed(), "the hand's section is hidden with geometry"
    pose = {"base": 0, "shoulder": 30, "elbow": 60, "wrist": 36, "wrist-rotate": 0, "gripper": 0}
    for n, v in pose.items():
        slide(n, v)
    wait("the arm at its pose", lambda: all(readback(n).startswith("%d.00°" % v)
                                            for n, v in pose.items()))

    def shown():
        w = one("#where")
        return {k: float(w.get_attribute("data-" + k)) for k in ("x", "y", "z", "pitch")}

    def where():
        if not through_lscd:
            return shown()  # the pty is lsc-panel's: the page is the only reader
        r = rig.lscctl("--port", "lscd:" + rig.sock, "--arm", os.environ["ARM"], "--json",
                       "where")
        j = json.loads(r.stdout)
        return {"x": j["x_mm"], "y": j["y_mm"], "z": j["z_mm"], "pitch": j["pitch_deg"]}

    def near(a, b, mm):
        return all(abs(a[k] - b[k]) <= mm for k in ("x", "y", "z"))

    def settled():
        """Where the grasp point is once two readings a read apart agree."""
        first = where()
        second = where()
        return second if near(first, second, 0.05) else None

    # the shown pose follows the arm (the servos reach the pose by their time)
    wait("#where to show lscctl where's pose within 1 mm",
         lambda: near(shown(), settled() or {"x": 1e9, "y": 0, "z": 0}, 1.0))
    at = settled() or wait("the arm to settle", settled)
    assert abs(shown()["pitch"] - at["pitch"]) <= 0.5, (shown(), at)
    assert one("#where-z").text == "%.1f" % shown()["z"], one("#where-z").text

    # z+ by the step, by keyboard
    step = float(one('input[name="jog-mm"]').get_attribute("value"))
    assert step == 10, step
    since = len(rig.log("sim"))
    one('button[data-jog="z+"]').send_keys(Keys.ENTER)
    wait("one move sent", lambda: len(rig.moves(since)) == 1)
    want = dict(at, z=at["z"] + step)
    wait("the grasp point %.1f mm up" % step, lambda: near(settled() or at, want, 2.0))
    got = wait("the arm to settle", settled)
    assert near(got, want, 2.0), (got, want)
    wait("#where to follow", lambda: near(shown(), got, 1.0))
    assert len(rig.moves(since)) == 1, rig.moves(since)

    # out of reach: the library's why in #status, nothing moves
    field = one('input[name="jog-mm"]')
    field.clear()
    field.send_keys("1000")
    since = len(rig.log("sim"))
    one('button[data-jog="z+"]').click()
    wait("the refusal in #status", lambda: "out of reach" in one("#status").text and
         "bad" in one("#status").get_attribute("class"))
    assert rig.moves(since) == [], rig.moves(since)
    field.clear()
    field.send_keys("10")


def no_geometry(d):
    """Without a profile's geometry, the hand's section is hidden."""
    rig = Rig()
    try:
        rig.start_panel(rig.tty, "--ids", "1-3")
        d.get(rig.url)
        wait_for("the joints", lambda: _try(lambda: len(d.find_elements(
            By.CSS_SELECTOR, "#joints input[type=range]")) == 3), 15)
        hand = d.find_element(By.ID, "hand")
        assert hand.get_attribute("hidden") is not None and not hand.is_displayed()
        print("ok: the hand's section is hidden without geometry")
    finally:
        codes = rig.close()
        assert codes[0] == 0, codes


def _try(cond):
    try:
        return cond()
    except Exception:  # an element not there yet: the wait goes on
        return False


def main():
    failures = 0
    shot = os.environ.get("SCREENSHOT") or None
    for through_lscd in (False, True):
        # the screenshot shows what an owner's would: lscd:ttyUSB0, files in
        # ~/.local/share/lsc/panel (the default --dir), no test paths
        rig = Rig(groups=os.environ["SIM_GROUPS"], tty="ttyUSB0")
        d = None
        mode = "through lscd" if through_lscd else "directly on lsc-sim's pty"
        try:
            home = os.path.join(rig.tmp, "home")
            os.mkdir(home)
            # --arm xarm, as the README shows it: the profile found by name
            env = dict(os.environ, HOME=home, LSC_ARMS_DIR=os.path.dirname(os.environ["ARM"]))
            env.pop("XDG_DATA_HOME", None)
            if through_lscd:
                rig.start_lscd()
                env["LSC_LSCD_DIR"] = rig.run
            rig.files = os.path.join(home, ".local", "share", "lsc", "panel")
            rig.start_panel("lscd:ttyUSB0" if through_lscd else rig.tty, "--arm", "xarm",
                            dir=None, env=env)
            d = browser()
            d.set_page_load_timeout(60 * scale())
            scenario(d, rig, through_lscd, shot if through_lscd else None)
            print("ok: the panel %s" % mode)
            if not through_lscd:
                no_geometry(d)
        except Exception as e:  # noqa: BLE001 - every failure is reported with its mode
            failures += 1
            print("FAIL: the panel %s: %s: %s" % (mode, type(e).__name__, e), file=sys.stderr)
            if d is not None:
                status = _try(lambda: d.find_element(By.ID, "status").text)
                print("  the page's status: %r; its console: %r" % (status, _try(
                    lambda: d.get_log("browser"))), file=sys.stderr)
            print("  lsc-panel's log: %r" % rig.log("panel")[-2000:], file=sys.stderr)
            if d is not None and os.environ.get("LSC_KEEP_TMP"):
                d.save_screenshot(os.path.join(rig.tmp, "failure.png"))
        finally:
            if d is not None:
                d.quit()
            codes = rig.close()
            if codes[0] != 0:
                failures += 1
                print("FAIL: lsc-panel exited %r after SIGTERM" % codes[0], file=sys.stderr)
    return 1 if failures else 0


if shutil.which("true") is not None:
    sys.exit(main())
