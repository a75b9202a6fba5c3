# Written for the PyPI xarm package: moves by id, by Servo, by lists of both,
# in positions and in degrees, waiting; positions read back; servos off.
import sys

import xarm

port = sys.argv[1] if len(sys.argv) > 1 else 'USB'
arm = xarm.Controller(port)

servo1 = xarm.Servo(1)
servo2 = xarm.Servo(2, 300)
servo3 = xarm.Servo(3, 90.0)

arm.setPosition(1, 300, duration=200, wait=True)
arm.setPosition(2, 700, 200, True)
arm.setPosition(3, 45.0, duration=200, wait=True)
print('1:', arm.getPosition(1), '2:', arm.getPosition(2), '3:', arm.getPosition(3, True))

arm.setPosition(servo2, duration=200, wait=True)
print('servo 2:', arm.getPosition(servo2))

arm.setPosition([servo1, servo3], duration=200, wait=True)
arm.setPosition([[4, 200], [5, 90.0]], duration=200, wait=True)
arm.setPosition([servo1, [6, 500], (2, -10.0)], None, 200, True)

servos = [xarm.Servo(1), xarm.Servo(2), xarm.Servo(3), xarm.Servo(4), xarm.Servo(5)]
arm.getPosition(servos)
for s in servos:
    print('servo %d: %d %.2f' % (s.servo_id, s.position, s.angle))

arm.servoOff(1)
arm.servoOff(servo2)
arm.servoOff([3, 4])
arm.servoOff([servo1, servo3])
arm.servoOff()
print('done')
