"""A campaign folder remembers its spec: the same spec resumes, another is refused or (overwrite) starts afresh."""

from __future__ import annotations

import json

import pytest

from seatwin.campaign import CampaignSpec
from seatwin.campaign.folder import SPEC_FILE, claim_folder, spec_fingerprint
from seatwin.cli.main import run
from seatwin.errors import ParameterError
from seatwin.outputs import OutputExistsError

SPEC = CampaignSpec(scenarios=("ferry_crossing",), seeds=(1,), duration=2.0, synthetic={"lidar_mode": ("raycast",)})
OTHER = CampaignSpec(scenarios=("ferry_crossing",), seeds=(1, 2), duration=2.0, synthetic={"lidar_mode": ("raycast",)})


def _earlier_results(out):
    (out / "jobs").mkdir(parents=True)
    (out / "jobs" / "0123.json").write_text("{}")
    (out / "results.csv").write_text("job_id\n")
    (out / "notes.txt").write_text("a user's file")


def test_the_same_spec_resumes_and_another_is_refused(tmp_path):
    out = tmp_path / "out"
    claim_folder(out, SPEC, "a.yaml")
    assert json.loads((out / SPEC_FILE).read_text())["fingerprint"] == spec_fingerprint(SPEC)
    _earlier_results(out)
    claim_folder(out, SPEC, "a.yaml")  # resume: nothing removed
    assert (out / "jobs" / "0123.json").exists() and (out / "results.csv").exists()
    with pytest.raises(OutputExistsError, match=r"another campaign \(a\.yaml, not b\.yaml\)") as err:
        claim_folder(out, OTHER, "b.yaml")
    assert err.value.param == "out" and (out / "results.csv").exists()
    assert json.loads((out / SPEC_FILE).read_text())["source"] == "a.yaml"


def test_overwrite_starts_afresh_and_keeps_a_users_files(tmp_path):
    out = tmp_path / "out"
    claim_folder(out, SPEC, "a.yaml")
    _earlier_results(out)
    claim_folder(out, OTHER, "b.yaml", overwrite=True)
    assert not (out / "jobs").exists() and not (out / "results.csv").exists()
    assert (out / "notes.txt").read_text() == "a user's file"
    assert json.loads((out / SPEC_FILE).read_text())["fingerprint"] == spec_fingerprint(OTHER)


def test_results_without_a_recorded_spec_are_not_mixed(tmp_path):
    out = tmp_path / "out"
    _earlier_results(out)
    with pytest.raises(OutputExistsError, match="holds campaign results with no record of their settings"):
        claim_folder(out, SPEC, "a.yaml")
    claim_folder(tmp_path / "fresh", SPEC, None)  # a folder with a user's files only is fine
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("x")
    claim_folder(tmp_path / "mine", SPEC, None)
    assert (tmp_path / "mine" / "notes.txt").read_text() == "x"


def test_a_changed_scenario_file_changes_the_fingerprint(tmp_path):
    scenario = tmp_path / "s.yaml"
    scenario.write_text("a")
    spec = SPEC.model_copy(update={"scenarios": (str(scenario),)})
    first = spec_fingerprint(spec)
    scenario.write_text("b")
    assert spec_fingerprint(spec) != first and spec_fingerprint(SPEC) == spec_fingerprint(SPEC.model_copy())


def test_the_output_is_never_an_input(tmp_path):
    spec_file = tmp_path / "c.yaml"
    spec_file.write_text("x")
    with pytest.raises(ParameterError, match="is the input"):
        claim_folder(spec_file, SPEC, str(spec_file))


def test_cli_refuses_another_campaign_before_any_job(tmp_path, capsys):
    out = tmp_path / "out"
    claim_folder(out, SPEC, "a.yaml")
    _earlier_results(out)
    spec = tmp_path / "b.yaml"
    spec.write_text("scenarios: [ferry_crossing]\nseeds: [3]\nduration: 2\nsynthetic: {lidar_mode: [raycast]}\n")
    assert run(["campaign", str(spec), "--out", str(out), "--workers", "0", "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "a.yaml" in err and str(spec) in err and "--overwrite" in err
    assert (out / "jobs" / "0123.json").exists()


def test_a_sweep_folder_remembers_its_settings(tmp_path, monkeypatch, capsys):
    """A finished sweep re-run with the same settings resumes; other settings are refused before any job runs."""
    import seatwin.campaign.engine
    from seatwin.sweep import run_sweep

    calls = []
    monkeypatch.setattr(seatwin.campaign.engine, "run_jobs", lambda jobs, *a, **k: calls.append(len(jobs)) or None)
    out = tmp_path / "sweep"
    out.mkdir()
    (out / "sweep.csv").write_text("an earlier sweep's rows")
    with pytest.raises(OutputExistsError, match="sweep results with no record of their settings") as err:
        run_sweep(out, kinds=("noise",), seeds=(1,), duration=5.0)
    assert err.value.param == "out_dir" and calls == []
    assert run(["sweep", "ferry_crossing", "--out", str(out), "--kinds", "noise", "--seeds", "1", "--duration", "5"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"seatwin: error: --out: {out} holds sweep results") and "--overwrite" in err
    assert calls == [] and (out / "sweep.csv").read_text() == "an earlier sweep's rows"
