#!/usr/bin/python3
"""lsc-panel finds an arm profile by name as lscctl does (lsc_arm_open), from a
directory that is not the source tree: --arm xarm is the user's
$XDG_CONFIG_HOME/lsc/arms/xarm.conf when there is one, else the installed one
($LSC_ARMS_DIR here); $LSC_ARM is the default of --arm (the systemd unit's
way, with lsc-panel@.service's environment file), but not with --ids; a name
found nowhere exits 2 saying where it looked.
Environment: LSC_PANEL, LSC_SIM, ARM (the xArm's profile in the tree),
PANEL_UNITS (the built units)."""
import http.client
import json
import os
import re
import select
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from panel_lib import Rig, scale, check, report  # noqa: E402



def joints(rig, env, *args):
    """Starts lsc-panel in rig.tmp/elsewhere with env and args; returns the
    names of the joints its /api/config lists."""
    p = rig.start([os.environ["LSC_PANEL"], "--port", rig.tty, "--listen", "127.0.0.1:0",
                   "--dir", rig.files, *args], cwd=os.path.join(rig.tmp, "elsewhere"),
                  env=env, stdout=subprocess.PIPE, text=True,
                  stderr=open(os.path.join(rig.tmp, "panel.log"), "w"))
    ready, _, _ = select.select([p.stdout], [], [], 20 * scale())
    line = p.stdout.readline().strip() if ready else ""
    m = re.fullmatch(r"http://127\.0\.0\.1:(\d+)/\?token=([0-9a-f]{32})", line)
    if not m:
        raise AssertionError("lsc-panel %s printed %r; its log: %s" % (args, line, rig.log("panel")))
    port, token = int(m.group(1)), m.group(2)
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=30 * scale())
    c.request("GET", "/api/config", headers={"Host": "127.0.0.1:%d" % port,
                                             "Cookie": "lsc_panel_%d=%s" % (port, token)})
    r = c.getresponse()
    data = r.read()
    c.close()
    p.terminate()
    p.wait(timeout=20 * scale())
    if r.status != 200:
        raise AssertionError("GET /api/config: %d %r" % (r.status, data))
    return [j["name"] for j in json.loads(data)["joints"]]


def main():
    # the systemd unit reads the arm from an environment file ($LSC_ARM), if
    # there is one (panel_http runs systemd-analyze verify on the unit)
    units = os.environ.get("PANEL_UNITS")
    if units:
        with open(os.path.join(units, "lsc-panel@.service")) as f:
            text = f.read()
        check("lsc-panel@.service reads /etc/lsc/panel-%i.conf when it exists",
              "\nEnvironmentFile=-/etc/lsc/panel-%i.conf\n" in text)
    rig = Rig()
    try:
        for d in ("elsewhere", "config/lsc/arms", "installed"):
            os.makedirs(os.path.join(rig.tmp, d))
        shutil.copy(os.environ["ARM"], os.path.join(rig.tmp, "installed", "xarm.conf"))
        env = {k: v for k, v in os.environ.items() if not k.startswith(("LSC_", "XDG_"))}
        env.update(XDG_CONFIG_HOME=os.path.join(rig.tmp, "config"),
                   LSC_ARMS_DIR=os.path.join(rig.tmp, "installed"))
        xarm = ["gripper", "wrist-rotate", "wrist", "elbow", "shoulder", "base"]

        got = joints(rig, env, "--arm", "xarm")
        check("--arm xarm: the installed profile's joints: %r" % got, got == xarm)
        got = joints(rig, dict(env, LSC_ARM="xarm"))
        check("$LSC_ARM=xarm: the installed profile's joints: %r" % got, got == xarm)
        got = joints(rig, dict(env, LSC_ARM="xarm"), "--ids", "1-2")
        check("--ids wins over $LSC_ARM: %r" % got, got == ["1", "2"])
        with open(os.path.join(rig.tmp, "config", "lsc", "arms", "xarm.conf"), "w") as f:
            f.write("hand 3 bus\n")
        got = joints(rig, env, "--arm", "xarm")
        check("the user's xarm comes first: %r" % got, got == ["hand"])

        r = subprocess.run([os.environ["LSC_PANEL"], "--port", "sim", "--arm", "xram"],
                           cwd=os.path.join(rig.tmp, "elsewhere"), env=env, capture_output=True,
                           text=True, stdin=subprocess.DEVNULL, timeout=30 * scale())
        want = ("lsc-panel: no arm profile named xram: looked for %s/config/lsc/arms/xram.conf, "
                "%s/installed/xram.conf (a file in this directory: ./xram)\n" % (rig.tmp, rig.tmp))
        check("--arm xram: exit 2 and where it looked, got %d %r" % (r.returncode, r.stderr),
              r.returncode == 2 and r.stderr == want and r.stdout == "")
    finally:
        rig.close()
    return report()


sys.exit(main())
