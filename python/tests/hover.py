"""The hover-recovery check of the C++ controller tests (tests/controllers/hover_recovery.hpp), from
Python: start at the hover trim at 3.5 m displaced by 1 m, command the trim position, fly the
ideal simulation (no uncertainty, wind or noise; RK4 1 ms, controller every step) and measure how
the position error settles."""

import numpy as np

import thetad


def hover_scenario(folder, trim, offset, duration):
    """A scenario file holding the trim position, starting `offset` (NED, m) away from it."""
    x = trim.state
    start = x[:3] + np.asarray(offset, dtype=float)
    listed = lambda values: "[" + ", ".join(repr(float(v)) for v in values) + "]"  # noqa: E731
    path = folder / f"hover-{'-'.join(str(v) for v in offset)}.yaml"
    path.write_text(
        f"""name: hover-recovery
duration: {duration}
initial_state:
  position: {listed([start[0], start[1], -start[2]])}
  velocity: {listed(x[3:6])}
  attitude: {listed(x[6:9])}
  rates: {listed(x[9:12])}
  flapping: {listed(x[12:14])}
phases:
  - type: step
    time: [0, {duration}]
    to: {listed([x[0], x[1], -x[2]])}
""")
    return str(path)


def recover_hover(folder, trim, controller, offset, duration, settle_band):
    """(result, settling time, final error): the last time the position error exceeded the band."""
    result = thetad.run(hover_scenario(folder, trim, offset, duration), controller, ideal=True, timing=False)
    frame = result.frame()
    error = np.linalg.norm(frame[["x_p_m", "y_p_m", "z_p_m"]].to_numpy() - frame[["x_c_m", "y_c_m", "z_c_m"]].to_numpy(),
                           axis=1)
    outside = frame["t_s"].to_numpy()[error > settle_band]
    return result, (outside[-1] if outside.size else 0.0), error[-1]
