"""``seatwin verify``: the campaign of closed-loop runs, its outputs and its errors."""

from __future__ import annotations

import csv
import json

import pytest

from seatwin.cli.main import run
from seatwin.errors import InputError
from seatwin.verification.campaign import newcombe, wilson
from seatwin.verification.spec import load_verify_spec


def test_intervals_against_hand_values():
    lo, hi = wilson(0, 10)
    assert lo == 0.0 and hi == pytest.approx(0.2775, abs=1e-4)  # Wilson 95 %: 0/10 → [0, 0.278]
    lo, hi = wilson(5, 10)
    assert (lo, hi) == pytest.approx((0.2366, 0.7634), abs=1e-4)
    d, lo, hi = newcombe(56, 70, 48, 80)  # Newcombe (1998) Table II example: 0.2 [0.0524, 0.3339]
    assert (d, lo, hi) == pytest.approx((0.2, 0.0524, 0.3339), abs=1e-4)


def test_bad_spec_names_the_field_and_line(tmp_path):
    p = tmp_path / "v.yaml"
    p.write_text("agents: [perfect]\nencounters: 0\n")
    with pytest.raises(InputError, match="line 2"):
        load_verify_spec(p)
    p.write_text("families: [head_on, collision]\n")
    with pytest.raises(InputError, match="collision"):
        load_verify_spec(p)


def test_seatwin_verify_writes_results_a_summary_and_a_map(tmp_path, capsys):
    spec = tmp_path / "v.yaml"
    spec.write_text("agents: [perfect]\nfamilies: [head_on, crossing_give_way]\nencounters: 2\ntcpa: [30, 40]\nrun_out: 40\n")
    out = tmp_path / "out"
    assert run(["verify", str(spec), "--out", str(out), "--workers", "0", "--no-progress"]) == 0
    printed = capsys.readouterr().out
    assert "perfect: 0 of 4 runs fail" in printed
    rows = list(csv.DictReader((out / "results.csv").open()))
    assert len(rows) == 4 and {r["family"] for r in rows} == {"head_on", "crossing_give_way"}
    assert all(r["passed"] == "True" for r in rows)
    summary = json.loads((out / "verify.json").read_text())
    assert summary["agents"]["perfect"]["runs"] == 4 and summary["cost"]["cpu_s_per_run_mean"] > 0
    assert (out / "failure_map.png").stat().st_size > 10_000
    # the same spec resumes from its jobs; another one is refused
    assert run(["verify", str(spec), "--out", str(out), "--workers", "0", "--no-progress"]) == 0
    spec.write_text("agents: [perfect]\nfamilies: [head_on]\nencounters: 2\ntcpa: [30, 40]\nrun_out: 40\n")
    assert run(["verify", str(spec), "--out", str(out), "--workers", "0", "--no-progress"]) == 2


def test_a_grpc_agent_beside_the_in_process_ones(tmp_path, capsys):
    """An external agent launched per run sails the same encounters; a dying one is one error row, not a crash."""
    import sys
    from pathlib import Path

    example = Path(__file__).resolve().parents[2] / "docs" / "examples" / "agents" / "grpc_agent.py"
    spec = tmp_path / "v.yaml"
    launch = f"[{json.dumps(sys.executable)}, {json.dumps(str(example))}, '{{address}}'"
    spec.write_text(
        "agents:\n  - perfect\n"
        f"  - {{kind: grpc, name: external, command: ['{{python}}', {json.dumps(str(example))}, '{{address}}']}}\n"
        f"  - {{kind: grpc, name: dying, command: {launch}, --die-at, '3'], timeout_s: 10}}\n"
        "families: [head_on]\nencounters: 1\ntcpa: [30, 30]\nrun_out: 10\nworst: 0\n"
    )
    out = tmp_path / "out"
    assert run(["verify", str(spec), "--out", str(out), "--workers", "0", "--no-progress"]) == 0
    captured = capsys.readouterr()
    rows = {r["agent"]: r for r in csv.DictReader((out / "results.csv").open())}
    assert set(rows) == {"perfect", "external", "dying"}
    assert rows["external"]["passed"] in ("True", "False") and int(rows["external"]["steps"]) > 300
    assert "exited with code 3: grpc_agent: dying at step 3" in rows["dying"]["error"]
    assert "run head_on_0000 (dying) failed: " in captured.err
    summary = json.loads((out / "verify.json").read_text())
    assert summary["agents"]["external"]["minus_perfect"]["pairs"] == 1


def test_bad_grpc_agents_are_named(tmp_path):
    p = tmp_path / "v.yaml"
    p.write_text("agents:\n  - {kind: grpc, name: x, command: [a], address: 'localhost:5'}\n")
    with pytest.raises(InputError, match="exactly one of command"):
        load_verify_spec(p)
    p.write_text("agents:\n  - perfect\n  - {kind: grpc, name: perfect, address: 'localhost:5'}\n")
    with pytest.raises(InputError, match="unique"):
        load_verify_spec(p)
    p.write_text("agents:\n  - {kind: grpc, name: x, address: 'localhost:5', sensors: [camera]}\n")
    with pytest.raises(InputError, match="sensors"):
        load_verify_spec(p)


def test_the_shipped_grpc_example_spec_is_valid_and_its_agent_is_beside_it():
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "docs" / "examples" / "agents" / "verify_grpc.yaml"
    spec = load_verify_spec(path)
    assert spec.agent_names == ("perfect", "example")
    ext = spec.agents[1]
    assert ext.command[0] == "{python}" and "{address}" in ext.command
    assert (path.parent / ext.command[1]).is_file()


def test_encounters_with_no_place_on_the_harbours_water_are_rows_not_runs(tmp_path):
    (tmp_path / "pond.yaml").write_text(
        "map_width: 30\nmap_height: 30\ngrid_resolution: 1.0\norigin_x_coordinate: -15\norigin_y_coordinate: -15\n"
    )
    (tmp_path / "pond.bin").write_bytes(bytes([1]) * 900)  # 30 m of water: no encounter fits
    spec = tmp_path / "v.yaml"
    spec.write_text("agents: [perfect]\nfamilies: [head_on]\nencounters: 2\nharbour: pond.yaml\n")
    out = tmp_path / "out"
    assert run(["verify", str(spec), "--out", str(out), "--workers", "0", "--no-progress"]) == 0
    rows = list(csv.DictReader((out / "results.csv").open()))
    assert [r["placed"] for r in rows] == ["False", "False"] and all("no place on water" in r["reasons"] for r in rows)
    summary = json.loads((out / "verify.json").read_text())
    assert summary["placement"]["families"]["head_on"] == {
        "placed": 0,
        "not_placed": 2,
        "rejected_draws": 0,
        "rejected_draws_mean": None,
        "rejected_draws_max": None,
    }
    assert summary["agents"]["perfect"]["runs"] == 0
