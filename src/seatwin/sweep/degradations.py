"""The degraded sensor models of the sweep: a kind, its strength's unit, and the simulator settings.

Each kind's strength is in the unit of the parameter it changes; ``reference`` is the value
of the reference model (standing in for reality) and a swept strength lies on either side of it
within ``[lo, hi]``: beyond it (a degraded model) or, where the kind allows, below it (a
*cleaner* model than reality — less noise, no drop — which a fidelity score must also see as
wrong); :func:`describe_reference` and :func:`describe_strengths` say it in words for
``seatwin sweep --help`` (these numbers' one source).
Each kind maps a strength to fields of :class:`seatwin.sim.SimulationSettings`
(``simulate_scenario(..., **d.settings(strength))``):

* ``noise`` — Gaussian range noise σ [m] (``range_noise``; reference 0.1 m, well above the
  VLP-16 preset's 0.015 m, so that a cleaner model has room below it).
* ``drop`` — ray-drop probability (``ray_drop``; the preset: 0.8, thesis 4.2.2; 0 = no drop).
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
    lo: float | None = None
    """Smallest strength (a cleaner model than the reference); None: only degradations beyond the reference."""

    def strength_problem(self, strength: float) -> str | None:
        """Why ``strength`` is not a swept strength of this kind (None when it is)."""
        lo = self.reference if self.lo is None else self.lo
        inside = (lo <= strength <= self.hi) if self.lo is not None else (lo < strength <= self.hi)
        if inside and strength != self.reference:
            return None
        bounds = f"[{lo:g}, {self.hi:g}]" if self.lo is not None else f"({lo:g}, {self.hi:g}]"
        unit = f" {self.unit}" if self.unit else ""
        return f"{self.kind} strength must be in {bounds}{unit} and differ from the reference {self.reference:g}"

    def direction(self, strength: float) -> str:
        """``degraded`` beyond the reference, ``cleaner`` below it."""
        return "cleaner" if strength < self.reference else "degraded"

    def settings(self, strength: float) -> dict[str, Any]:
        """:class:`seatwin.sim.SimulationSettings` field values of the reference model with this kind at ``strength``
        (a ``ParameterError`` outside the range)."""
        problem = self.strength_problem(strength)
        if problem is not None:
            raise ParameterError("strengths", f"{problem}, got {strength}")
        return {**reference_model(), **self.fields(float(strength))}


DEGRADATIONS: dict[str, Degradation] = {
    d.kind: d
    for d in (
        Degradation("noise", "m", "range noise σ [m]", 0.1, (0.0, 0.03, 0.2, 0.4, 0.8), lambda s: {"range_noise": s}, lo=0.0),
        Degradation(
            "drop",
            "",
            "ray-drop probability",
            VLP16.drop_probability,
            (0.0, 0.5, 0.9, 0.95, 0.98),
            lambda s: {"ray_drop": s},
            hi=0.999,
            lo=0.0,
        ),
        Degradation(
            "dissipation", "", "range dissipation (0 off, 1 on)", 0.0, (1.0,), lambda s: {"dissipation": bool(s)}, hi=1.0
        ),
        Degradation(
            "mount", "deg", "mount yaw bias [deg]", 0.0, (0.5, 1.0, 2.0, 4.0), lambda s: {"mount_yaw_bias_deg": s}, hi=90.0
        ),
    )
}


def _values(values: Sequence[float], unit: str) -> str:
    return ",".join(f"{v:g}" for v in values) + (f" {unit}" if unit else "")


def describe_reference() -> str:
    """The reference model in words, from :data:`DEGRADATIONS` (e.g. "range noise σ 0.1 m, ray-drop probability 0.8, …")."""
    return ", ".join(f"{d.kind} {_values([d.reference], d.unit)}" for d in DEGRADATIONS.values())


def describe_strengths() -> str:
    """Each kind's default strengths and allowed range in words, from :data:`DEGRADATIONS`."""
    parts = []
    for d in DEGRADATIONS.values():
        hi = "∞)" if d.hi == float("inf") else f"{d.hi:g}]"
        allowed = f"({d.reference:g}, {hi}" if d.lo is None else f"[{d.lo:g}, {hi} but {d.reference:g}"
        parts.append(f"{d.kind} {_values(d.default_strengths, d.unit)} (any in {allowed})")
    return "; ".join(parts)


def reference_model() -> dict[str, Any]:
    """:class:`seatwin.sim.SimulationSettings` field values of the reference model: every kind at its reference."""
    out: dict[str, Any] = {}
    for d in DEGRADATIONS.values():
        out.update(d.fields(d.reference))
    return out


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
