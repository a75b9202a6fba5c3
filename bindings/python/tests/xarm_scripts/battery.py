# Written for the PyPI xarm package: connect, read the battery, list the servos.
import sys

import xarm

port = sys.argv[1] if len(sys.argv) > 1 else 'USB'
arm = xarm.Controller(port)
print('Battery voltage in volts:', arm.getBatteryVoltage())
servos = arm.listServos()
print('Servos:', servos)
