"""The reference agent: seatwin's perception (or ground truth) → COLREG velocity obstacles → LOS guidance → a
speed/heading set-point. Three variants by name (:data:`VARIANTS`):

* ``reference`` — lidar and radar through clustering and JIPDA (:class:`~seatwin.agents.perception.TrackingPerception`);
* ``perfect`` — the same avoidance fed the targets' true states;
* ``late`` — ``reference`` reacting only 10 s before a closest approach (a deliberately weakened agent).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from seatwin.agents.avoidance import AvoidanceParameters, choose_velocity, los_guidance
from seatwin.agents.interface import Command, Mission, Navigation, SensorFrame, SetPoint, TrackEstimate
from seatwin.agents.perception import PerfectPerception, TrackingPerception
from seatwin.encounters.geometry import Kind
from seatwin.errors import ParameterError


class ReferenceAgent:
    """See the module docstring. ``perception``: ``sensors`` (lidar/radar tracking) or ``truth``."""

    def __init__(
        self,
        name: str = "reference",
        perception: str = "sensors",
        sensors: tuple[str, ...] = ("lidar", "radar"),
        avoidance: AvoidanceParameters | None = None,
        tuning: str = "synthetic",
    ):
        if perception not in ("sensors", "truth"):
            raise ParameterError("perception", f"expected 'sensors' or 'truth', got {perception!r}")
        bad = [s for s in sensors if s not in ("lidar", "radar")]
        if perception == "sensors" and (bad or not sensors):
            raise ParameterError("sensors", f"expected one or both of 'lidar', 'radar', got {list(sensors)}")
        self.name = name
        self.perception_kind = perception
        self.sensors = ("truth",) if perception == "truth" else tuple(sensors)
        self.params = avoidance or AvoidanceParameters()
        self.tuning = tuning
        self.mission: Mission | None = None
        self._perception: TrackingPerception | PerfectPerception | None = None
        self._previous: float | None = None
        self.acting_on: dict[int, Kind] = {}
        """The tracks the last step avoided, with their COLREG situation."""

    def reset(self, mission: Mission) -> None:
        self.mission = mission
        self._perception = (
            PerfectPerception() if self.perception_kind == "truth" else TrackingPerception(mission.harbour, self.tuning)
        )
        self._previous = None
        self.acting_on = {}

    def tracks(self) -> list[TrackEstimate]:
        return [] if self._perception is None else self._perception.tracks()

    def step(self, time: float, frames: Sequence[SensorFrame], navigation: Navigation) -> Command:
        if self.mission is None or self._perception is None:
            raise ParameterError("mission", "the agent was not reset with a mission before its first step")
        self._perception.update(frames)
        speed, course = los_guidance(navigation, self.mission, self.params)
        speed, course, self.acting_on = choose_velocity(
            navigation, speed, course, self.tracks(), self.params, self._previous, self.acting_on, self.mission.cruise_speed
        )
        self._previous = course if self.acting_on else None
        return SetPoint(speed, course)


LATE_REACTION_S = 10.0


def make_agent(variant: str, **kwargs: object) -> ReferenceAgent:
    """The reference agent ``reference``, ``perfect`` or ``late`` (:data:`VARIANTS`)."""
    if variant == "reference":
        return ReferenceAgent("reference", "sensors", **kwargs)  # type: ignore[arg-type]
    if variant == "perfect":
        return ReferenceAgent("perfect", "truth", **kwargs)  # type: ignore[arg-type]
    if variant == "late":
        p = replace(AvoidanceParameters(), reaction_time=LATE_REACTION_S, stand_on_time=min(LATE_REACTION_S, 15.0))
        return ReferenceAgent("late", "sensors", avoidance=p, **kwargs)  # type: ignore[arg-type]
    raise ParameterError("agent", f"unknown agent {variant!r}; expected one of {', '.join(VARIANTS)}")


VARIANTS = ("reference", "perfect", "late")
