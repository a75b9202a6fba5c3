# Written for the PyPI xarm package: wave the hand a few times, then rest.
import sys

import xarm

port = sys.argv[1] if len(sys.argv) > 1 else 'USB'
arm = xarm.Controller(port)

arm.setPosition([[3, 500], [4, 500], [5, 500]], duration=300, wait=True)
for i in range(3):
    arm.setPosition(6, 300, duration=150, wait=True)
    arm.setPosition(6, 700, duration=150, wait=True)
    print('wave', i + 1, 'at', arm.getPosition(6))
arm.setPosition(6, 500, duration=150, wait=True)
print('rest:', [arm.getPosition(i) for i in range(3, 7)])
