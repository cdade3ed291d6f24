"""The fidelity method's seeds as jobs of the campaign engine (:mod:`seatwin.campaign.engine`).

One job per (radar model, seed): simulate the replica with that model and seed, track it with every
agent, return the plots and the tracks (as exact JSON). The driver (:func:`seatwin.fidelity.method.run_fidelity`)
compares and pools them. Jobs run in this process or on Ray, and resume from ``DIR/jobs``: results are
the same bits either way (every draw is keyed by the seed).
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from seatwin.campaign.engine import Job
    from seatwin.evaluation import Tracks
    from seatwin.fidelity.joyride import JoyrideData
    from seatwin.perception.measurements import Scan
    from seatwin.sensors.radar.config import RadarConfig
    from seatwin.tracking import TrackerConfig

KIND = "fidelity_seed"


def seed_job(
    dataset: str | Path,
    model: str,
    config: RadarConfig,
    seed: int,
    tuning: TrackerConfig,
    agents: tuple[str, ...],
    untruthed: dict[str, NDArray[np.float64]],
) -> Job:
    """The job simulating radar ``config`` (labelled ``model``) with ``seed`` on the replica of ``dataset``
    (plus the ``untruthed`` vessels' rows), tracked by each of ``agents`` with ``tuning``."""
    from seatwin.campaign.engine import Job

    return Job(
        {
            "kind": KIND,
            "dataset": str(Path(dataset).resolve()),
            "model": model,
            "radar": config.model_dump(mode="json"),
            "seed": int(seed),
            "tuning": tuning.model_dump(mode="json"),
            "agents": list(agents),
            "untruthed": {name: np.asarray(rows, float).tolist() for name, rows in untruthed.items()},
        }
    )


def tracker_scans(time: NDArray[np.float64], plots: list[NDArray[np.float64]], antenna: NDArray[np.float64]) -> list[Scan]:
    """Range–bearing radar scans for the tracker (world frame, about the antenna; no land mask, no
    merging: the joyride recording's own hint), through :func:`seatwin.perception.radar.radar_scan`."""
    from seatwin.perception.radar import radar_scan

    return [radar_scan(p, float(t), float(a[0]), float(a[1])) for t, p, a in zip(time, plots, antenna)]


def run_agent(scans: list[Scan], tuning: TrackerConfig, agent: str) -> Tracks:
    """Agent ``jipda`` or ``gnn`` over ``scans`` (:func:`seatwin.pipeline.track_scans`)."""
    from seatwin.pipeline import track_scans

    return track_scans(scans, tuning, agent=agent)


@lru_cache(maxsize=4)
def _dataset(path: str) -> JoyrideData:
    from seatwin.fidelity.joyride import load_joyride

    return load_joyride(path)


def seed_run(params: dict[str, Any], inputs: dict[str, Any]) -> dict[str, Any]:
    """The engine's job function (:data:`seatwin.campaign.engine.JobFn`) of a :func:`seed_job`."""
    from seatwin.campaign.job import tracks_to_json
    from seatwin.fidelity.joyride import replica_scene, simulate_replica
    from seatwin.sensors.radar.config import RadarConfig
    from seatwin.sensors.radar.model import RadarModel
    from seatwin.tracking import TrackerConfig

    data = _dataset(params["dataset"])
    extra = {name: np.asarray(rows, float) for name, rows in params["untruthed"].items()}
    scene = replica_scene(data, extra=extra or None)
    config = RadarConfig.model_validate(params["radar"])
    tuning = TrackerConfig.model_validate(params["tuning"])
    scans = simulate_replica(data, RadarModel(config, seed=params["seed"]), scene)
    plots = [sc.positions for sc in scans]
    antenna = np.array([[sc.antenna.north, sc.antenna.east] for sc in scans])
    tscans = tracker_scans(data.time, plots, antenna)
    return {
        "plots": [np.asarray(p, float).tolist() for p in plots],
        "tracks": {agent: tracks_to_json(run_agent(tscans, tuning, agent)) for agent in params["agents"]},
    }


def seed_outputs(result: dict[str, Any]) -> tuple[list[NDArray[np.float64]], dict[str, Tracks]]:
    """A :func:`seed_run` result back as plots per scan and tracks per agent."""
    from seatwin.campaign.job import tracks_from_json

    plots = [np.asarray(p, float).reshape(-1, 2) for p in result["plots"]]
    return plots, {agent: tracks_from_json(t) for agent, t in result["tracks"].items()}
