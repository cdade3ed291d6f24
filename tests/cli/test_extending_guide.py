"""docs/extending.md runs as written: its commands in order (outputs under a temporary ``runs/``), on the example
files shipped in docs/examples/extending/, and they do what the page says."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import numpy as np
import pytest

from seatwin.cli.main import run

ROOT = Path(__file__).resolve().parents[2]
GUIDE = ROOT / "docs" / "extending.md"
EXAMPLE = ROOT / "docs" / "examples" / "extending"


def guide_commands() -> list[str]:
    """Every ``seatwin …`` line of the guide's ```bash blocks, in order."""
    blocks = re.findall(r"```bash\n(.*?)```", GUIDE.read_text(encoding="utf-8"), flags=re.S)
    return [line.strip() for b in blocks for line in b.splitlines() if line.strip().startswith("seatwin ")]


def guide_yaml() -> list[str]:
    """The guide's ```yaml blocks."""
    return re.findall(r"```yaml\n(.*?)```", GUIDE.read_text(encoding="utf-8"), flags=re.S)


def test_the_guide_is_linked_and_quotes_the_example_as_it_is():
    assert "docs/extending.md" in (ROOT / "README.md").read_text(encoding="utf-8")
    scenario = (EXAMPLE / "my_scenario.yaml").read_text(encoding="utf-8")
    for block in guide_yaml():
        assert block in scenario, f"the guide quotes what my_scenario.yaml does not hold:\n{block}"
    assert len(guide_commands()) == 4


def test_the_guides_commands_run_and_do_what_it_says(tmp_path, monkeypatch, capsys):
    from seatwin.scenario.load import load_scenario
    from seatwin.sensors.lidar import lidar_for_scenario, sweep_to_world
    from seatwin.world.scene import Scene

    monkeypatch.chdir(ROOT)
    outputs = []
    for cmd in guide_commands():
        argv = [a.replace("runs/", f"{tmp_path}/runs/") for a in shlex.split(cmd)[1:]]
        code = run(argv)
        out, err = capsys.readouterr()
        assert code == 0, f"{cmd}\n{err}"
        outputs.append((cmd, out, err))
    # 1. rasterize: the shipped raster is the command's output, byte for byte.
    made = tmp_path / "runs" / "extending"
    for suffix in (".yaml", ".bin"):
        assert (made / f"my_harbour{suffix}").read_bytes() == (EXAMPLE / f"my_harbour{suffix}").read_bytes(), suffix
    assert "202 × 162 cells of 1 m" in outputs[0][1]
    # 2. scenario info: the mesh file in the model column, both vessels 100 % on water, no warning.
    info = outputs[1][1]
    assert info.startswith("my_harbour_crossing")
    assert re.search(r"Skiff\s+target\s+skiff\.obj\s.*100 %", info) and re.search(r"milliAmpere\s+ownship.*100 %", info)
    assert "on land" not in outputs[1][2]
    # 3. plot and simulate wrote their files; the run keeps the mesh and its placement.
    assert (made / "my_scenario.png").stat().st_size > 10_000
    run_sc = load_scenario(made / "run" / "scenario.yaml")
    skiff = run_sc.vessel("Skiff")
    assert Path(skiff.model).resolve() == (EXAMPLE / "skiff.obj").resolve()
    assert (skiff.mesh.scale, skiff.mesh.yaw_deg, skiff.mesh.offset) == (0.01, 90.0, (0.0, 0.0, 0.4))
    # The mesh as the YAML places it: 6 m long with its bow forward, 2.2 m wide, 0.4 m below and 1.6 m above water.
    sc = load_scenario(EXAMPLE / "my_scenario.yaml")
    scene = Scene.from_scenario(sc)
    model = scene.vessel_models["Skiff"]
    lo, hi = model.mesh.bounds
    assert (model.length, model.beam) == pytest.approx((6.0, 2.2))
    assert (lo[0], hi[0], lo[2], hi[2]) == pytest.approx((-2.8, 3.2, -1.6, 0.4))
    # "the lidar sees the quays and the skiff": one sweep 12 s in has returns on the skiff's hull and on land.
    lidar = lidar_for_scenario(sc, scene)
    sweep = lidar.sweep(sc.start + 12.0, 120)
    world = sweep_to_world(lidar, sweep)
    pose = scene.pose("Skiff", sc.start + 12.0)
    d = np.hypot(world[:, 0] - float(pose.north), world[:, 1] - float(pose.east))
    assert (d < 3.5).sum() >= 5
    # the quays: returns at least 45 m east or west of the harbour's centre line
    assert (np.abs(world[:, 1]) > 45).sum() > 100
