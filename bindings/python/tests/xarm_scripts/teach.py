# Written for the PyPI xarm package: teach poses (the arm moved to each, its
# positions kept as Servo objects), then play them back twice.
import sys
import time

import xarm

port = sys.argv[1] if len(sys.argv) > 1 else 'USB'
pause = float(sys.argv[2]) if len(sys.argv) > 2 else 0.5
arm = xarm.Controller(port)

poses = []
for target in (200, 400, 600):
    arm.setPosition([[2, target], [3, 1000 - target]], duration=100, wait=True)
    pose = [xarm.Servo(2), xarm.Servo(3)]
    arm.getPosition(pose)
    poses.append(pose)
    print('taught:', [(s.servo_id, s.position, s.angle) for s in pose])

for rep in range(2):
    for pose in poses:
        # as scripts often write it: position (ignored for a list), then duration
        arm.setPosition(pose, 1000, True)
        time.sleep(pause)
        got = [arm.getPosition(s) for s in pose]
        print('replay', rep + 1, got, got == [s.position for s in pose])
arm.servoOff()
print('done')
