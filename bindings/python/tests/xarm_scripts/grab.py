# Written for the PyPI xarm package: check the battery, open the gripper,
# close it on an object, lift it, put it down and let go.
import sys

import xarm

port = sys.argv[1] if len(sys.argv) > 1 else 'USB'
arm = xarm.Controller(port)

volts = arm.getBatteryVoltage()
print('Battery voltage in volts:', volts)
if volts < 6.0:
    print('battery low')
    sys.exit(1)

gripper = xarm.Servo(1, 200)
arm.setPosition(gripper, duration=500, wait=True)
print('open at', arm.getPosition(1))
arm.setPosition(1, 700, duration=500, wait=True)
held = arm.getPosition(1)
print('closed at', held, '(holding something)' if held < 690 else '(empty)')
arm.setPosition([[3, 300], [4, 700]], duration=500, wait=True)
print('lifted:', arm.getPosition(3), arm.getPosition(4))
arm.setPosition([[3, 500], [4, 500]], duration=500, wait=True)
arm.setPosition(gripper, duration=500, wait=True)
print('let go at', arm.getPosition(1))
