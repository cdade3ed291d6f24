"""The shipped example logs are the generator's output and give back their vessels."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.groundtruth.examples import EXAMPLES_DIR, write_example_logs


def test_shipped_examples_equal_the_generator(tmp_path):
    written = write_example_logs(tmp_path)
    assert len(written) == 5
    for path in written:
        assert (EXAMPLES_DIR / path.name).read_bytes() == path.read_bytes(), path.name


def test_examples_make_a_scenario(tmp_path):
    from seatwin.groundtruth import compute_ground_truth
    from seatwin.groundtruth.examples import BASELINE_M, ORIGIN
    from seatwin.groundtruth.vessel import VesselSpec

    e = EXAMPLES_DIR
    vessels = [
        VesselSpec("Havfruen", (e / "havfruen_bow.pos", e / "havfruen_stern.pos"), BASELINE_M),
        VesselSpec("milliAmpere", (e / "milliampere.nmea",)),
    ]
    result = compute_ground_truth(vessels, ORIGIN)
    hav = result.vessels[0]
    assert hav.name == "Havfruen" and len(hav.time) == 601  # 60 s on the 10 Hz common clock
    assert abs(float(hav.eps_gnss.mean())) < 0.05  # 2 cm antenna noise
    # The generator's Havfruen: heading 60° turning 0.5°/s, from (-60, -40) m at 2.5 m/s.
    assert np.degrees(hav.heading[[0, -1]]) == pytest.approx([60.0, 90.0], abs=2.0)
    assert (hav.north[0], hav.east[0]) == pytest.approx((-60.0, -40.0), abs=0.2)
    assert np.hypot(hav.v_north, hav.v_east)[100:-100] == pytest.approx(2.5, abs=0.1)


def _example_args(out, *extra: str) -> list[str]:
    """``seatwin groundtruth`` on the shipped examples, as the README runs it."""
    from seatwin.groundtruth.examples import BASELINE_M, ORIGIN

    e = EXAMPLES_DIR
    return [
        "groundtruth", "--origin", f"{ORIGIN.lat_deg},{ORIGIN.lon_deg}",
        "--vessel", f"Havfruen={e / 'havfruen_bow.pos'},{e / 'havfruen_stern.pos'},{BASELINE_M}",
        "--vessel", f"Finn={e / 'finn.gpx'}", "--vessel", f"milliAmpere={e / 'milliampere.nmea'}",
        "--out", str(out), *extra,
    ]  # fmt: skip


def test_examples_import_to_a_named_scenario_on_water(tmp_path, shared_data, capsys):
    """The README's import of the examples: a scenario named after the file (or ``--name``), the last vessel the
    ownship, in harbour ravnkloa, and every vessel on the real raster's water (aligned as shipped) in ≥ 99.5 %
    of its samples — the examples are an example of good data."""
    from seatwin.cli.main import run
    from seatwin.layout import harbour_map
    from seatwin.scenario.load import load_scenario
    from seatwin.scenario.on_water import land_samples

    out = tmp_path / "gt" / "ravnkloa_example.yaml"
    assert run(_example_args(out)) == 0
    sc = load_scenario(out)
    assert sc.name == "ravnkloa_example"
    assert [v.name for v in sc.vessels] == ["Havfruen", "Finn", "milliAmpere"]
    assert sc.ownship is not None and sc.ownship.name == "milliAmpere"
    assert sc.environment["harbour"] == "ravnkloa"
    assert [v.model for v in sc.vessels] == ["havfruen", "finn", "milliampere"]
    raster = harbour_map("ravnkloa")
    on_land = {s.vessel: s.count / s.samples for s in land_samples(sc, raster)}
    assert all(on_land.get(v.name, 0.0) <= 0.005 for v in sc.vessels), on_land
    # The Gemini CSV beside the YAML reads back as the same frame (the Ravnkloa origin, no shift).
    csv = load_scenario(out.with_suffix(".csv"))
    assert csv.origin == sc.origin
    assert csv.vessels[0].trajectory.north == pytest.approx(sc.vessels[0].trajectory.north)

    named = tmp_path / "named" / "s.yaml"
    assert run(_example_args(named, "--name", "Ravnkloa canal", "--ownship", "Finn")) == 0
    sc2 = load_scenario(named)
    assert sc2.name == "Ravnkloa canal" and sc2.ownship.name == "Finn"
    assert run(_example_args(tmp_path / "open" / "s.yaml", "--harbour", "none")) == 0
    assert load_scenario(tmp_path / "open" / "s.yaml").environment["harbour"] == "none"


def test_example_vessels_keep_apart():
    """Without the real raster: the generator's tracks keep apart (no collisions) and move as specified."""
    from seatwin.groundtruth.examples import DURATION_S, TRACK_SPECS, _track

    t = np.arange(0.0, DURATION_S + 1e-9, 0.2)
    tracks = {name: _track(t, *spec) for name, spec in TRACK_SPECS.items()}
    names = list(tracks)
    for i, a in enumerate(names):
        for b in names[i + 1 :]:
            d = np.hypot(tracks[a][0] - tracks[b][0], tracks[a][1] - tracks[b][1])
            assert d.min() > 15.0, (a, b, d.min())


@pytest.mark.parametrize(
    ("extra", "flag"),
    [(["--name", "x"], "--name"), (["--ownship", "milliAmpere"], "--ownship"), (["--harbour", "none"], "--harbour")],
)
def test_a_csv_cannot_hold_a_name_and_says_so(tmp_path, capsys, extra, flag):
    from seatwin.cli.main import run

    out = tmp_path / "s.csv"
    assert run(_example_args(out, *extra)) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"seatwin: error: {flag}:") and "scenario .yaml" in err[0], err
    assert not out.exists()


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (["--ownship", "Nobody"], ["--ownship", "Nobody", "Havfruen, Finn, milliAmpere"]),
        (["--harbour", "nowhere.yaml"], ["--harbour", "nowhere.yaml", "not found"]),
        (["--harbour", "atlantis"], ["--harbour", "expected a harbour name"]),
        (["--name", " "], ["--name", "non-empty"]),
    ],
)
def test_bad_scenario_options_are_refused_before_any_work(tmp_path, capsys, extra, words):
    from seatwin.cli.main import run

    out = tmp_path / "s.yaml"
    assert run(_example_args(out, *extra)) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and all(w in err for w in words), err
    assert not out.exists() and not out.with_suffix(".csv").exists()
