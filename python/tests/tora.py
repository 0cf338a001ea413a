"""The RTAC/TORA benchmark written in Python: core/tora_plant.cpp line for line (the same operations in the
same order, so that a flight of it and of the shipped "tora" agree bit for bit), in plain floats, which
cost less than numpy on 4-vectors."""

import math

import thetad


class PythonTora(thetad.Plant):
    state_dim, input_dim = 4, 1
    state_names = ["xi", "xi_dot", ("theta", "rad"), ("theta_dot", "rad_per_s")]
    input_names = ["torque"]
    initial_state = [1.0, 0.0, 0.0, 0.0]

    def __init__(self, epsilon=0.2):
        self.epsilon = epsilon

    def f(self, x, u):
        x0, x1, x2, x3 = x.tolist()
        e, s, c = self.epsilon, math.sin(x2), math.cos(x2)
        d = 1.0 - e * e * c * c
        return [x1, (-x0 + e * x3 * x3 * s - e * c * u[0]) / d, x3, (e * c * (x0 - e * x3 * x3 * s) + u[0]) / d]

    def sdc(self, x, u):
        _, _, x2, x3 = x.tolist()
        e, s, c = self.epsilon, math.sin(x2), math.cos(x2)
        d = 1.0 - e * e * c * c
        F = [[0.0, 1.0, 0.0, 0.0],
             [-1.0 / d, 0.0, 0.0, e * x3 * s / d],
             [0.0, 0.0, 0.0, 1.0],
             [e * c / d, 0.0, 0.0, -e * e * c * s * x3 / d]]
        return F, [[0.0], [-e * c / d], [0.0], [1.0 / d]]

    def jacobian(self, x, u):
        x0, _, x2, w = x.tolist()
        u0 = float(u[0])
        e, s, c = self.epsilon, math.sin(x2), math.cos(x2)
        d, dd = 1.0 - e * e * c * c, 2.0 * e * e * c * s
        n2 = -x0 + e * w * w * s - e * c * u0
        n4 = e * c * (x0 - e * w * w * s) + u0
        A = [[0.0, 1.0, 0.0, 0.0],
             [-1.0 / d, 0.0, (e * w * w * c + e * s * u0) / d - n2 * dd / (d * d), 2.0 * e * w * s / d],
             [0.0, 0.0, 0.0, 1.0],
             [e * c / d, 0.0, (-e * s * x0 - e * e * w * w * (c * c - s * s)) / d - n4 * dd / (d * d),
              -2.0 * e * e * c * s * w / d]]
        return A, [[0.0], [-e * c / d], [0.0], [1.0 / d]]
