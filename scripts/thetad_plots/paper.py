"""Which of the paper's figures (Xin, Xu & Hopkins 2011, Sec. 4) a thetad figure corresponds to.

The paper prints eight figures per scenario, all for θ–D in the disturbed setting: Figs. 2–9 for
scenario I (takeoff, hover, figure 8, hover, landing) and Figs. 10–17 for scenario II (takeoff, a
descending and climbing circle, hover). The scenario files scenarios/scenario-1.yaml and
scenario-2.yaml are thetad's concrete versions of the two; a figure of any other scenario has no
counterpart in the paper, nor have the comparison figures (tracking error, compute time, summary).
"""

# thetad figure kind -> (paper's caption in its words, Fig. of scenario I, Fig. of scenario II).
FIGURES = {
    "trajectory_3d": ("three-dimensional view of the trajectory", 2, 10),
    "position": ("time histories of the position tracking", 3, 11),
    "euler_angles": ("Euler angle responses", 4, 12),
    "angular_rates": ("angular velocity responses", 5, 13),
    "body_velocities": ("translational velocity responses", 6, 14),
    "flapping_angles": ("flapping angle responses", 7, 15),
    "control_deflections": ("control deflections", 8, 16),
    "main_rotor_thrust": ("main rotor thrust", 9, 17),
}
SCENARIOS = {"scenario-1": ("I", 1), "scenario-2": ("II", 2)}


def figure_number(kind, scenario):
    """The paper's figure number for a thetad figure `kind` of the scenario named `scenario`, or
    None where the paper has no such figure."""
    if kind not in FIGURES or scenario not in SCENARIOS:
        return None
    return FIGURES[kind][SCENARIOS[scenario][1]]

