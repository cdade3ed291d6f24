"""The degraded sensor models of the sweep: a kind, its strength's unit, and the simulator settings.

Each kind's strength is in the unit of the parameter it changes; ``reference`` is the value
of the reference model (the VLP-16 preset as is, nominal mount) and every swept strength must
lie beyond it. Each kind maps a strength to keyword arguments of
:func:`seatwin.sim.simulate_scenario`:

* ``noise`` — Gaussian range noise σ [m] (the preset: 0.015 m).
* ``drop`` — ray-drop probability (the preset: 0.8, thesis 4.2.2).
* ``dissipation`` — range-dependent return probability off (0) or on (1).
* ``mount`` — the lidar simulated turned by this many degrees of yaw more than the nominal
  mount recorded on ``/tf_static`` (a miscalibrated extrinsic the tracker cannot see).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from seatwin.errors import InputError
from seatwin.sensors.lidar_config import VLP16


@dataclass(frozen=True)
class Degradation:
    """One kind of degraded sensor model."""

    kind: str
    unit: str
    label: str
    reference: float
    default_strengths: tuple[float, ...]
    kwargs: Callable[[float], dict[str, Any]]
    hi: float = float("inf")

    def settings(self, strength: float) -> dict[str, Any]:
        """Keyword arguments of ``simulate_scenario`` for ``strength`` (validated)."""
        if not self.reference < strength <= self.hi:
            raise InputError("--strengths", f"{self.kind} strength must be in ({self.reference}, {self.hi}] "
                                            f"{self.unit} (beyond the reference model), got {strength}")
        return self.kwargs(float(strength))


DEGRADATIONS: dict[str, Degradation] = {
    d.kind: d
    for d in (
        Degradation("noise", "m", "range noise σ [m]", VLP16.range_noise_std, (0.05, 0.1, 0.2, 0.4),
                    lambda s: {"range_noise": s}),
        Degradation("drop", "", "ray-drop probability", VLP16.drop_probability, (0.85, 0.9, 0.95, 0.98),
                    lambda s: {"ray_drop": s}, hi=0.999),
        Degradation("dissipation", "", "range dissipation (0 off, 1 on)", 0.0, (1.0,),
                    lambda s: {"dissipation": True}, hi=1.0),
        Degradation("mount", "deg", "mount yaw bias [deg]", 0.0, (0.5, 1.0, 2.0, 4.0),
                    lambda s: {"mount_yaw_bias_deg": s}, hi=90.0),
    )
}


def degradation(kind: str) -> Degradation:
    """The degradation ``kind`` (``InputError`` naming the known kinds otherwise)."""
    try:
        return DEGRADATIONS[kind]
    except KeyError:
        raise InputError("--kinds", f"unknown degradation {kind!r}; expected some of {', '.join(DEGRADATIONS)}") from None


def parse_kinds(text: str) -> list[Degradation]:
    """A comma-separated list of kinds, in the given order, without repeats."""
    names = [p.strip() for p in text.split(",") if p.strip()]
    if not names:
        raise InputError("--kinds", f"expected a comma-separated list of {', '.join(DEGRADATIONS)}")
    if len(set(names)) != len(names):
        raise InputError("--kinds", f"a kind is repeated in {text!r}")
    return [degradation(n) for n in names]
