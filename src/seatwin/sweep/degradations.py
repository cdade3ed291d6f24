"""The degraded sensor models of the sweep: a kind, its strength's unit, and the simulator settings.

Each kind's strength is in the unit of the parameter it changes; ``reference`` is the value
of the reference model (the VLP-16 preset as is, nominal mount) and every swept strength must
lie beyond it. Each kind maps a strength to fields of :class:`seatwin.sim.SimulationSettings`
(``simulate_scenario(..., **d.settings(strength))``):

* ``noise`` — Gaussian range noise σ [m] (``range_noise``; the preset: 0.015 m).
* ``drop`` — ray-drop probability (``ray_drop``; the preset: 0.8, thesis 4.2.2).
* ``dissipation`` — range-dependent return probability off (0) or on (1) (``dissipation``).
* ``mount`` — the lidar simulated turned by this many degrees of yaw more than the nominal
  mount recorded on ``/tf_static`` (``mount_yaw_bias_deg``; a miscalibrated extrinsic the
  tracker cannot see).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from seatwin.errors import ParameterError
from seatwin.sensors.lidar_config import VLP16


@dataclass(frozen=True)
class Degradation:
    """One kind of degraded sensor model."""

    kind: str
    unit: str
    label: str
    reference: float
    default_strengths: tuple[float, ...]
    fields: Callable[[float], dict[str, Any]]
    """Strength → :class:`seatwin.sim.SimulationSettings` field values."""
    hi: float = float("inf")

    def strength_problem(self, strength: float) -> str | None:
        """Why ``strength`` is not a degradation of this kind (None when it is)."""
        if self.reference < strength <= self.hi:
            return None
        return f"{self.kind} strength must be in ({self.reference}, {self.hi}] {self.unit} (beyond the reference model)"

    def settings(self, strength: float) -> dict[str, Any]:
        """:class:`seatwin.sim.SimulationSettings` field values for ``strength`` (a ``ParameterError`` outside the range)."""
        problem = self.strength_problem(strength)
        if problem is not None:
            raise ParameterError("strengths", f"{problem}, got {strength}")
        return self.fields(float(strength))


DEGRADATIONS: dict[str, Degradation] = {
    d.kind: d
    for d in (
        Degradation(
            "noise", "m", "range noise σ [m]", VLP16.range_noise_std, (0.05, 0.1, 0.2, 0.4), lambda s: {"range_noise": s}
        ),
        Degradation(
            "drop",
            "",
            "ray-drop probability",
            VLP16.drop_probability,
            (0.85, 0.9, 0.95, 0.98),
            lambda s: {"ray_drop": s},
            hi=0.999,
        ),
        Degradation("dissipation", "", "range dissipation (0 off, 1 on)", 0.0, (1.0,), lambda s: {"dissipation": True}, hi=1.0),
        Degradation(
            "mount", "deg", "mount yaw bias [deg]", 0.0, (0.5, 1.0, 2.0, 4.0), lambda s: {"mount_yaw_bias_deg": s}, hi=90.0
        ),
    )
}


def degradation(kind: str) -> Degradation:
    """The degradation ``kind`` (a ``ParameterError`` naming the known kinds otherwise)."""
    try:
        return DEGRADATIONS[kind]
    except KeyError:
        raise ParameterError("kinds", f"unknown degradation {kind!r}; expected some of {', '.join(DEGRADATIONS)}") from None


def degradations(kinds: Sequence[str]) -> list[Degradation]:
    """The degradations ``kinds``, in the given order (none, a repeat or an unknown kind is a ``ParameterError``)."""
    if not kinds:
        raise ParameterError("kinds", f"no degradation to sweep; expected some of {', '.join(DEGRADATIONS)}")
    if len(set(kinds)) != len(kinds):
        raise ParameterError("kinds", f"a kind is repeated in {', '.join(kinds)}")
    return [degradation(k) for k in kinds]
