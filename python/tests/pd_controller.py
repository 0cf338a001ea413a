"""A hover PD controller written in Python: position errors become attitude and thrust commands,
attitude errors cyclic and pedal commands, around a trim. The gains are the C++ example PID's
(controllers/examples/pid.hpp) without its integral terms; plain floats, since numpy's per-call
overhead on 3-vectors costs more than the arithmetic."""

import math

import thetad


class HoverPD(thetad.Controller):
    def __init__(self, trim, mass=8.2, gravity=9.81):
        super().__init__()
        self.state, self.input = trim.state.tolist(), trim.input.tolist()
        self.mass, self.gravity = mass, gravity

    def compute(self, t, x, reference):
        x, r = x.tolist(), reference.position.tolist()
        psi = x[8]
        c, s = math.cos(psi), math.sin(psi)
        ex, ey, ez = x[0] - r[0], x[1] - r[1], x[2] - r[2]
        forward, right = c * ex + s * ey, -s * ex + c * ey
        # Heading-frame velocity from the body velocity, to first order in roll and pitch.
        vx, vy, vz = x[3] + x[7] * x[5], x[4] - x[6] * x[5], x[5] - x[7] * x[3] + x[6] * x[4]
        ax, ay, az = -forward - 1.6 * vx, -right - 1.6 * vy, -12.0 * ez - 6.0 * vz
        pitch, roll = self.state[7] - ax / self.gravity, self.state[6] + ay / self.gravity
        heading_error = math.remainder(psi - self.state[8], 2.0 * math.pi)
        return [self.input[0] - self.mass * az,
                self.input[1] + 0.073 * heading_error + 0.029 * x[11],
                self.input[2],
                self.input[3] + 0.05 * (pitch - x[7]),
                self.input[4] + 0.08 * (roll - x[6])]
