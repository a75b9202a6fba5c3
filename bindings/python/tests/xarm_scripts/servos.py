# Written for the PyPI xarm package: Servo objects, positions and angles.
import xarm

servo = xarm.Servo(1, 300)
print('servo ID:', servo.servo_id)
print('servo position:', servo.position)
print('servo angle:', servo.angle)

servo = xarm.Servo(3, 90.0)
print('servo 3:', servo.position, servo.angle)
servo.angle = -45.1
print('servo 3:', servo.position, servo.angle)
servo.position = 1000
print('servo 3:', servo.position, servo.angle)
print('default:', xarm.Servo(2).position, xarm.Servo(2).angle)
