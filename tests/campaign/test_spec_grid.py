"""Campaign files: validation with errors naming the file and field; the grid's jobs, their order and ids."""

from __future__ import annotations

import pytest

from seatwin.campaign import CampaignSpec, Job, expand_grid, job_id, load_campaign
from seatwin.campaign.grid import REFERENCE, SYNTHETIC, window_offset
from seatwin.cli.main import run
from seatwin.errors import InputError, ParameterError

EXAMPLE = """\
scenarios: [ferry_crossing, stop_and_evade]
seeds: [1, 2, 3]
duration: 20
synthetic: {lidar_mode: [depthbuffer, raycast]}
reference: {lidar_mode: raycast}
tunings: [synthetic]
"""


def _write(tmp_path, text, name="campaign.yaml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_the_docs_example_loads_and_expands():
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "docs" / "examples" / "campaign.yaml"
    spec = load_campaign(path)
    assert spec.synthetic == {"lidar_mode": ("depthbuffer", "raycast")}
    assert spec.reference == {"lidar_mode": "raycast"} and spec.tunings == ("synthetic",)
    grid = expand_grid(spec)
    n = len(spec.scenarios) * len(spec.seeds)
    assert len(grid.synthetic_jobs) == 2 * n and len(grid.reference_jobs) == n


def test_grid_order_ids_and_shared_references(tmp_path):
    spec = load_campaign(_write(tmp_path, EXAMPLE + "reference_seed_offset: 100\n"))
    grid = expand_grid(spec)
    syn, refs = grid.synthetic_jobs, grid.reference_jobs
    assert len(syn) == 2 * 2 * 3 and len(refs) == 2 * 3  # each reference once per (scenario, reference seed)
    order = [(j.params["scenario"], j.params["settings"]["lidar_mode"], j.params["seed"]) for j in syn]
    assert order[:4] == [
        ("ferry_crossing", "depthbuffer", 1),
        ("ferry_crossing", "depthbuffer", 2),
        ("ferry_crossing", "depthbuffer", 3),
        ("ferry_crossing", "raycast", 1),
    ]
    assert order[6][0] == "stop_and_evade"
    seen = set()
    for job in grid.jobs:  # each reference comes before the first job that needs it
        assert all(n in seen for n in job.needs)
        seen.add(job.id)
    by_id = {j.id: j for j in grid.jobs}
    for job in syn:
        (ref_id,) = job.needs
        ref = by_id[ref_id].params
        assert ref["kind"] == REFERENCE and job.params["kind"] == SYNTHETIC
        assert ref["seed"] == job.params["seed"] + 100 == job.params["reference_seed"]  # never the same draws
        assert ref["settings"] == {"lidar_mode": "raycast"} and ref["scenario"] == job.params["scenario"]
        centred = {"ferry_crossing": 27.5, "stop_and_evade": 30.0}[ref["scenario"]]  # 20 s centred in 75 s / 80 s
        assert ref["start_offset"] == job.params["start_offset"] == centred
    # ids are hashes of the parameters: stable across runs, distinct across jobs
    assert [j.id for j in expand_grid(load_campaign(tmp_path / "campaign.yaml")).jobs] == [j.id for j in grid.jobs]
    assert len(set(by_id)) == len(grid.jobs)
    assert all(j.id == job_id(j.params) and len(j.id) == 16 for j in grid.jobs)


def test_job_id_ignores_key_order_but_not_values():
    assert job_id({"a": 1, "b": [1, 2]}) == job_id({"b": [1, 2], "a": 1})
    assert job_id({"a": 1}) != job_id({"a": 2})
    assert job_id({"x": 0.1}) != job_id({"x": 0.1 + 1e-16 * 2})
    assert Job({"t": (1, 2)}).params == {"t": [1, 2]}  # tuples become lists: what a job file reads back
    with pytest.raises(ParameterError, match="finite JSON"):
        job_id({"x": float("nan")})


def test_values_are_validated_and_normalised(tmp_path):
    spec = load_campaign(
        _write(
            tmp_path,
            "scenarios: [ferry_crossing]\nseeds: [4]\nduration: 2\n"
            "synthetic: {range_noise: [0, 0.05], sensors: [[lidar], [lidar, radar]]}\nreference: {range_noise: 0.015}\n",
        )
    )
    assert spec.synthetic == {"range_noise": (0.0, 0.05), "sensors": (["lidar"], ["lidar", "radar"])}
    assert spec.n_points() == 4 and spec.varied == ("range_noise", "sensors")
    settings = [j.params["settings"] for j in expand_grid(spec).synthetic_jobs]
    assert settings[1] == {"range_noise": 0.0, "sensors": ["lidar", "radar"]}


def test_relative_files_are_relative_to_the_campaign_file(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "tune.yaml").write_text("base: synthetic\n")
    spec = load_campaign(_write(tmp_path / "sub", "scenarios: [ferry_crossing]\nseeds: [1]\nduration: 1\ntunings: [tune.yaml]\n"))
    assert spec.tunings == (str((tmp_path / "sub" / "tune.yaml").resolve()),)


SYN = "line 4, field synthetic"


@pytest.mark.parametrize(
    ("text", "where", "what"),
    [
        (
            EXAMPLE.replace("depthbuffer, raycast", "depthbuffer, laser"),
            "line 4, field synthetic",
            "lidar_mode: expected 'raycast'",
        ),
        (
            EXAMPLE.replace("[depthbuffer, raycast]", "raycast"),
            "line 4, field synthetic",
            "lidar_mode: expected a list of values",
        ),
        (EXAMPLE.replace("lidar_mode: [", "lidar_moed: ["), SYN, "lidar_moed: not a simulation setting"),
        (
            EXAMPLE.replace("lidar_mode: [", "seed: [1, 2], lidar_mode: ["),
            "line 4, field synthetic",
            "seed: not a simulation setting",
        ),
        (EXAMPLE.replace("[depthbuffer, raycast]", "[raycast, raycast]"), SYN, "expected distinct values"),
        (
            EXAMPLE.replace("{lidar_mode: raycast}", "{ray_drop: 1.5}"),
            "line 5, field reference",
            "ray_drop: expected a value less than 1",
        ),
        (EXAMPLE.replace("[1, 2, 3]", "[1, 1]"), "line 2, field seeds", "expected distinct seeds"),
        (EXAMPLE.replace("seeds: [1, 2, 3]\n", ""), "seeds", "Field required"),
        (EXAMPLE.replace("duration: 20", "duration: -1"), "line 3, field duration", "greater than 0"),
        (EXAMPLE.replace("[synthetic]", "[sinthetic]"), "line 6, field tunings", "not a tuning preset"),
        (EXAMPLE + "colour: blue\n", "line 7, field colour", "Extra inputs are not permitted"),
    ],
)
def test_bad_fields_name_the_file_and_field(tmp_path, text, where, what):
    path = _write(tmp_path, text)
    with pytest.raises(InputError) as err:
        load_campaign(path)
    assert err.value.source == str(path) and err.value.where == where, str(err.value)
    assert what in err.value.detail


def test_bad_files(tmp_path):
    with pytest.raises(InputError, match="not valid YAML") as err:
        load_campaign(_write(tmp_path, "scenarios: [a\nseeds: 1\n"))
    assert err.value.where.startswith("line ")
    with pytest.raises(InputError, match="expected a mapping of campaign fields"):
        load_campaign(_write(tmp_path, "- 1\n- 2\n"))
    with pytest.raises(InputError, match="cannot open"):
        load_campaign(tmp_path / "missing.yaml")


def test_scenarios_and_windows_are_checked_before_any_job(tmp_path):
    path = _write(tmp_path, EXAMPLE.replace("stop_and_evade", "no_such_scenario"))
    with pytest.raises(InputError) as err:
        expand_grid(load_campaign(path), path)
    assert err.value.source == str(path) and err.value.where == "scenarios" and "no_such_scenario" in err.value.detail
    path = _write(tmp_path, EXAMPLE.replace("duration: 20", "duration: 78"))
    with pytest.raises(InputError, match=r"scenario ferry_crossing: the window \[0, 78\] s is not inside its 75 s") as err:
        expand_grid(load_campaign(path), path)
    assert err.value.where == "duration"
    assert window_offset(75.0, 20.0, 50.0, "x") == 50.0
    with pytest.raises(ParameterError) as perr:
        window_offset(75.0, 20.0, 60.0, "x")
    assert perr.value.param == "offset"


def test_spec_in_code_names_parameters():
    with pytest.raises(ParameterError) as err:
        CampaignSpec(scenarios=("ferry_crossing",), seeds=(1,), duration=1, synthetic={"dissipation": ["maybe"]})
    assert err.value.param == "synthetic" and "dissipation" in err.value.detail


def test_cli_bad_campaign_file_exits_2_with_one_line(tmp_path, capsys):
    path = _write(tmp_path, EXAMPLE.replace("depthbuffer, raycast", "depthbuffer, laser"))
    assert run(["campaign", str(path), "--out", str(tmp_path / "out"), "--workers", "0"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"seatwin: error: {path}: line 4, field synthetic: lidar_mode: expected 'raycast'") and "\n" not in err
    assert not (tmp_path / "out" / "jobs").exists()
    assert run(["campaign", str(tmp_path / "nope.yaml"), "--out", str(tmp_path / "out")]) == 2
    assert "cannot open" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("text", "where", "what"),
    [
        (
            'a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]\nb: &b [*a,*a,*a,*a,*a,*a,*a,*a,*a]\n'
            "c: &c [*b,*b,*b,*b,*b,*b,*b,*b,*b]\nd: &d [*c,*c,*c,*c,*c,*c,*c,*c,*c]\ne: &e [*d,*d,*d,*d,*d,*d,*d,*d,*d]\n"
            "f: &f [*e,*e,*e,*e,*e,*e,*e,*e,*e]\ng: &g [*f,*f,*f,*f,*f,*f,*f,*f,*f]\nh: &h [*g,*g,*g,*g,*g,*g,*g,*g,*g]\n"
            "scenarios: *h\n",
            "line 1, column 4",
            "anchor &a: YAML anchors and aliases are not accepted",
        ),
        (EXAMPLE + "reference_seed_offset: &x 5\nduration2: *x\n", "line 7, column 24", "anchor &x"),
        (EXAMPLE + "synthetic2: " + "[" * 1000 + "]" * 1000 + "\n", "line 7, column 76", "nested deeper than 64 levels"),
        (EXAMPLE + "reference_seed_offset: " + "7" * 5000 + "\n", "line 7, column 24", "integer of 5000 characters"),
        (EXAMPLE.replace("duration: 20", "duration: .inf"), "line 3, column 11", "expected a finite number, got .inf"),
    ],
)
def test_hostile_yaml_is_refused_with_file_and_line(tmp_path, text, where, what):
    path = _write(tmp_path, text)
    with pytest.raises(InputError) as err:
        load_campaign(path)
    assert err.value.source == str(path) and err.value.where == where, str(err.value)
    assert what in err.value.detail


@pytest.mark.parametrize("value", ["inf", "-inf", "nan", "1e999"])
def test_non_finite_numbers_written_as_words_are_refused(tmp_path, value):
    """YAML reads ``inf`` and ``1e999`` as strings; the settings still refuse them as numbers."""
    for text, where in (
        (EXAMPLE.replace("duration: 20", f"duration: {value}"), "line 3, field duration"),
        (EXAMPLE.replace("{lidar_mode: raycast}", f"{{range_noise: {value}}}"), "line 5, field reference"),
        (EXAMPLE + f"comparison: {{gate: {value}}}\n", "line 7, field comparison"),
    ):
        with pytest.raises(InputError, match="finite number") as err:
            load_campaign(_write(tmp_path, text))
        assert err.value.where == where


def test_cli_refuses_an_alias_bomb_at_once(tmp_path, capsys):
    path = _write(tmp_path, "a: &a [1, 2]\nb: [*a, *a]\n" + EXAMPLE)
    assert run(["campaign", str(path), "--out", str(tmp_path / "out"), "--workers", "0"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (
        f"seatwin: error: {path}: line 1, column 4: anchor &a: YAML anchors and aliases are not accepted "
        "(they can expand without bound); write the value out"
    )
