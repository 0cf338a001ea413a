"""A plant besides the helicopter from Python (docs/plants.md): the RTAC/TORA benchmark by its shipped
scenario files and by name, flown by theta-D, the SDRE and the LQR at the plant's design point."""

import pytest

import thetad


def test_the_registry_lists_the_benchmark():
    assert "tora" in [plant["name"] for plant in thetad.plants()]


def test_a_plant_flies_by_name_from_its_own_or_a_given_initial_state():
    flown = thetad.run(plant="tora", controller="sdre", duration_s=1, timing=False)
    assert flown.completed and flown.provenance["plant"] == "tora"
    assert flown.provenance["initial_state"] == [1.0, 0.0, 0.0, 0.0]
    assert flown.columns[:5] == ["t_s", "xi", "xi_dot", "theta_rad", "theta_dot_rad_per_s"]
    moved = thetad.run(plant="tora", controller="theta-d", initial_state=[0.5, 0, 0, 0], duration_s=1, timing=False)
    assert moved.provenance["initial_state"] == [0.5, 0.0, 0.0, 0.0]


def test_the_shipped_scenarios_fly_every_controller_and_match_the_shorthand():
    results = thetad.compare("tora/regulation", ["theta-d", "sdre", "lqr"], duration_s=1, timing=False)
    assert [r.label for r in results] == ["theta-d", "sdre", "lqr"] and all(r.completed for r in results)
    assert results[0].provenance["scenario"]["name"] == "tora-regulation"
    shorthand = thetad.run(plant="tora", controller="sdre", duration_s=1, timing=False)
    assert shorthand.summary["cost"] == results[1].summary["cost"]
    strong = thetad.run("tora/strong-coupling", "lqr", duration_s=1, timing=False)
    assert strong.completed and strong.provenance["initial_state"] == [1.5, 0.0, 0.0, 0.0]


def test_the_optimum_and_the_bench_take_a_plants_scenario():
    report = thetad.optimal("tora/regulation", ["sdre"], horizon=0.5, cost="j", control_interval=0.1, timing=False)
    assert report.converged
    assert report.report["controllers"][0]["gap_percent"] > -1e-3


def test_what_does_not_apply_to_a_plant_is_an_error():
    with pytest.raises(thetad.Error, match="scenario or a registered plant"):
        thetad.run("tora/regulation", "sdre", plant="tora", duration_s=1)
    with pytest.raises(thetad.Error, match="without disturbances or actuator limits"):
        thetad.run(plant="tora", controller="sdre", duration_s=1, wind_gust=True)
