# Written for the PyPI xarm package: angles in degrees, Servo angles kept as
# given, positions read back in degrees.
import sys

import xarm

port = sys.argv[1] if len(sys.argv) > 1 else 'USB'
arm = xarm.Controller(port)

s = xarm.Servo(3, 90.1)
print('servo 3:', s.position, s.angle)
s.position = 90.0
print('position 90.0:', s.position, s.angle)
s.angle = -30
print('angle -30:', s.position, s.angle)

arm.setPosition(3, 45.0, duration=200, wait=True)
arm.setPosition(s, duration=200, wait=True)
arm.setPosition(4, -45.5, duration=200, wait=True)
arm.setPosition([[5, 12.3], [6, -125.0]], duration=200, wait=True)
for i in (3, 4, 5, 6):
    print('servo', i, arm.getPosition(i), arm.getPosition(i, degrees=True))
