"""A small campaign database of format_version 4, with the column and meta names thetad wrote before
docs/glossary.md's (campaigns/campaign_store.cpp then): what the report must still read. Two labels
over two cells of a swept initial_offset_x and three draws; lqr's last draw of cell 1 diverged.
The figures are simple functions of (label, cell, draw), so a test can say what the report gives."""

import json
import sqlite3

FACTORS = ["uncertainty_scale", "gust_scale", "gust_onset", "noise_scale", "initial_offset_x", "initial_offset_y",
           "initial_offset_z", "initial_offset_roll", "initial_offset_pitch", "initial_offset_yaw",
           "trajectory_speed_scale", "course", "actuator_limits", "turbulence_model", "turbulence_intensity",
           "turbulence_scale", "servo_delay", "servo_time_constant", "dt", "duration"]
METRICS = ["rms_x_m", "rms_y_m", "rms_z_m", "rms_error_m", "max_x_m", "max_y_m", "max_z_m", "max_error_m", "cost",
           "cost_dev", "effort_thrust_N", "effort_pedal_rad", "effort_collective_rad", "effort_longitudinal_rad",
           "effort_lateral_rad", "compute_us_mean", "compute_us_median", "compute_us_p99", "wall_s"]
LABELS = ["td", "lqr"]
OFFSETS = [0.0, 0.5]  # initial_offset_x, per cell
DRAWS = 3
REASON = "roll |phi| = 1.5 rad exceeds 1.4835 rad at t = 0.412 s"


def rms_error(label, cell, draw):
    return (0.1 if label == "td" else 0.2) + 0.1 * cell + 0.01 * draw


def completed(label, cell, draw):
    return not (label == "lqr" and cell == 1 and draw == DRAWS - 1)


def metrics(label, cell, draw):
    rms = rms_error(label, cell, draw)
    return {"rms_x_m": 0.6 * rms, "rms_y_m": 0.8 * rms, "rms_z_m": 0.0, "rms_error_m": rms,
            "max_x_m": 1.5 * rms, "max_y_m": 2.0 * rms, "max_z_m": 0.1 * rms, "max_error_m": 2.0 * rms,
            "cost": 1000.0 * rms, "cost_dev": 10.0 * rms, "effort_thrust_N": 60.0 + draw, "effort_pedal_rad": 0.01,
            "effort_collective_rad": 0.02, "effort_longitudinal_rad": 0.03, "effort_lateral_rad": 0.04,
            "compute_us_mean": 5.0 + draw, "compute_us_median": 4.0 + draw, "compute_us_p99": 9.0 + draw,
            "wall_s": 0.25}


def write(path):
    """Writes the database to `path` (a new file)."""
    columns = ["cell", "draw", "scenario", "controller", "seed", *FACTORS, "status", "reason", "information",
               "end_time_s", "controller_samples", *METRICS]
    text = ("campaign: old\nscenarios: [scenario-1]\ncontrollers: [{label: td, controller: theta-d}, "
            "{controller: lqr}]\ndraws: {count: 3}\nfixed: {duration: 1}\n"
            "sweep: {grid: {initial_offset_x: [0, 0.5]}}\n")
    meta = {"format": "thetad-campaign-1", "format_version": "4", "campaign_name": "old",
            "campaign_file": "/nowhere/old.yaml", "campaign_text": text, "campaign_sha256": "0" * 64, "shard": "1/1",
            "run_count": str(len(OFFSETS) * DRAWS * len(LABELS)), "draws": str(DRAWS),
            "swept": json.dumps(["initial_offset_x"]), "controllers": json.dumps(LABELS),
            "scenarios": json.dumps(["/nowhere/scenario-1.yaml"]), "provenance": "[]"}
    with sqlite3.connect(path) as db:
        db.execute("CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL)")
        db.execute(f"CREATE TABLE runs (run_index INTEGER PRIMARY KEY, {', '.join(columns)})")
        db.executemany("INSERT INTO meta (key, value) VALUES (?, ?)", meta.items())
        index = 0
        for cell, offset in enumerate(OFFSETS):
            for draw in range(DRAWS):
                for label in LABELS:
                    done = completed(label, cell, draw)
                    factors = {"initial_offset_x": offset, "duration": 1.0}
                    row = [index, cell, draw, "scenario-1", label, str(1000 + draw),
                           *[factors.get(name) for name in FACTORS],
                           "completed" if done else "diverged", "" if done else REASON, "none",
                           1.0 if done else 0.412, 1000 if done else 412,
                           *[metrics(label, cell, draw)[name] for name in METRICS]]
                    db.execute(f"INSERT INTO runs VALUES ({', '.join('?' * len(row))})", row)
                    index += 1
    db.close()
