"""Encounters as points of a parameter space, and samplers over it: random, Latin hypercube, adaptive.

An :class:`EncounterSpace` maps the unit cube [0, 1)ᵈ to encounters: the ownship's speed, then (CPA, TCPA, relative
course, speed) of each target within the ranges of its COLREG kind (:data:`RANGES`). The ranges are chosen so every
point is the kind it is drawn for (:func:`~seatwin.encounters.geometry.situation`; tested over the whole cube).
Samplers return unit-cube points (so any space can be searched) and are deterministic for a seed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from seatwin.encounters.geometry import Kind, TargetGeometry, situation
from seatwin.errors import ParameterError


@dataclass(frozen=True)
class KindRanges:
    """Ranges of one kind's target parameters: (low, high) each."""

    cpa: tuple[float, float]
    """m, signed"""
    tcpa: tuple[float, float]
    """s"""
    relative_course_deg: tuple[float, float]
    speed: tuple[float, float]
    """m/s"""


RANGES: dict[Kind, KindRanges] = {
    Kind.HEAD_ON: KindRanges(cpa=(-20.0, 20.0), tcpa=(50.0, 100.0), relative_course_deg=(170.0, 190.0), speed=(1.0, 3.0)),
    Kind.CROSSING_GIVE_WAY: KindRanges(
        cpa=(-20.0, 20.0), tcpa=(50.0, 100.0), relative_course_deg=(-135.0, -60.0), speed=(1.0, 3.0)
    ),
    Kind.CROSSING_STAND_ON: KindRanges(
        cpa=(-20.0, 20.0), tcpa=(50.0, 100.0), relative_course_deg=(60.0, 135.0), speed=(1.0, 3.0)
    ),
    Kind.OVERTAKING: KindRanges(cpa=(-15.0, 15.0), tcpa=(50.0, 100.0), relative_course_deg=(-15.0, 15.0), speed=(0.3, 0.8)),
}
"""Target ranges by kind, for an ownship at :data:`OWN_SPEED` (milliAmpere's 1.5–2.2 m/s service speeds)."""

OWN_SPEED = (1.5, 2.2)
"""m/s"""


@dataclass(frozen=True)
class Encounter:
    """An encounter: the ownship's speed and its targets' geometry without avoidance."""

    own_speed: float
    targets: tuple[TargetGeometry, ...]
    kinds: tuple[Kind, ...]
    """The COLREG kind each target was drawn as."""
    run_out: float = 30.0
    """Seconds the ownship sails on after the last closest approach to its goal (the scenario then runs
    :data:`seatwin.encounters.place.SLACK_S` longer)."""

    @property
    def duration(self) -> float:
        return max(t.tcpa for t in self.targets) + self.run_out

    @property
    def situations(self) -> tuple[Kind, ...]:
        """The kinds the geometry classifies as (equal to :attr:`kinds` for points of :data:`RANGES`)."""
        return tuple(situation(self.own_speed, t) for t in self.targets)

    def parameters(self) -> dict[str, float | str]:
        """A flat record (results tables): own_speed, then kind_i, cpa_i, tcpa_i, relative_course_deg_i, speed_i."""
        out: dict[str, float | str] = {"own_speed": self.own_speed}
        for i, (t, k) in enumerate(zip(self.targets, self.kinds), start=1):
            out |= {
                f"kind_{i}": k.value,
                f"cpa_{i}": t.cpa,
                f"tcpa_{i}": t.tcpa,
                f"relative_course_deg_{i}": math.degrees(t.relative_course),
                f"speed_{i}": t.speed,
            }
        return out


@dataclass(frozen=True)
class EncounterSpace:
    """The unit cube → encounters with one target per entry of ``kinds``."""

    kinds: tuple[Kind, ...]
    own_speed: tuple[float, float] = OWN_SPEED
    ranges: dict[Kind, KindRanges] = field(default_factory=lambda: dict(RANGES))
    run_out: float = 30.0

    def __post_init__(self) -> None:
        if not self.kinds:
            raise ParameterError("kinds", "an encounter needs at least one target kind")
        missing = [k.value for k in self.kinds if k not in self.ranges]
        if missing:
            raise ParameterError("kinds", f"no parameter ranges for {missing}; known: {[k.value for k in self.ranges]}")

    @property
    def dimension(self) -> int:
        return 1 + 4 * len(self.kinds)

    def encounter(self, u: NDArray[np.float64] | list[float]) -> Encounter:
        """The encounter at unit-cube point ``u`` (d values in [0, 1])."""
        x = np.asarray(u, dtype=float).reshape(-1)
        if x.shape[0] != self.dimension or not ((x >= 0) & (x <= 1)).all():
            raise ParameterError("u", f"expected {self.dimension} values in [0, 1], got {x.tolist()}")

        def lerp(r: tuple[float, float], v: float) -> float:
            return float(r[0] + (r[1] - r[0]) * v)

        targets = []
        for i, k in enumerate(self.kinds):
            r, v = self.ranges[k], x[1 + 4 * i : 5 + 4 * i]
            targets.append(
                TargetGeometry(
                    cpa=lerp(r.cpa, v[0]),
                    tcpa=lerp(r.tcpa, v[1]),
                    relative_course=math.radians(lerp(r.relative_course_deg, v[2])),
                    speed=lerp(r.speed, v[3]),
                )
            )
        return Encounter(lerp(self.own_speed, x[0]), tuple(targets), self.kinds, self.run_out)


SPACES: dict[str, tuple[Kind, ...]] = {
    "head_on": (Kind.HEAD_ON,),
    "crossing_give_way": (Kind.CROSSING_GIVE_WAY,),
    "crossing_stand_on": (Kind.CROSSING_STAND_ON,),
    "overtaking": (Kind.OVERTAKING,),
    "multi": (Kind.HEAD_ON, Kind.CROSSING_GIVE_WAY),
}
"""Encounter families by name: one target of each kind, and ``multi`` (head-on and a give-way crossing at once)."""


def space(name: str, run_out: float = 30.0, tcpa: tuple[float, float] | None = None) -> EncounterSpace:
    """The :class:`EncounterSpace` of a family of :data:`SPACES`; ``tcpa`` (low, high) [s] replaces every kind's TCPA
    range (shorter encounters fit a harbour: a crossing target sails tcpa × speed metres before the CPA)."""
    if name not in SPACES:
        raise ParameterError("family", f"unknown encounter family {name!r}; expected one of {', '.join(SPACES)}")
    ranges = dict(RANGES)
    if tcpa is not None:
        if not (0 < tcpa[0] <= tcpa[1] and math.isfinite(tcpa[1])):
            raise ParameterError("tcpa", f"expected 0 < low ≤ high, got {tcpa}")
        ranges = {k: replace(r, tcpa=(float(tcpa[0]), float(tcpa[1]))) for k, r in ranges.items()}
    return EncounterSpace(SPACES[name], ranges=ranges, run_out=run_out)


def random_points(dimension: int, n: int, seed: int) -> NDArray[np.float64]:
    """``n`` independent uniform points of [0, 1)^dimension."""
    return np.random.default_rng(seed).random((n, dimension))


def latin_hypercube(dimension: int, n: int, seed: int) -> NDArray[np.float64]:
    """``n`` points of a Latin hypercube (``scipy.stats.qmc.LatinHypercube``): each axis's n strata hit once."""
    from scipy.stats import qmc

    return qmc.LatinHypercube(d=dimension, seed=np.random.default_rng(seed)).random(n)


@dataclass(frozen=True)
class Trial:
    """One evaluated point of a search."""

    index: int
    point: tuple[float, ...]
    score: float
    """The evaluation's robustness: < 0 a failure (e.g. minimum distance − safety distance)."""


class TrialLog:
    """A search's trials so far: :meth:`run` evaluates one point, :meth:`initial_design` a Latin hypercube; both
    say whether the search should stop (a failure, score < 0, with ``stop_at_failure``)."""

    def __init__(self, evaluate: Callable[[NDArray[np.float64]], float], stop_at_failure: bool) -> None:
        self.evaluate, self.stop_at_failure = evaluate, stop_at_failure
        self.trials: list[Trial] = []

    def run(self, u: NDArray[np.float64]) -> bool:
        score = float(self.evaluate(u))
        self.trials.append(Trial(len(self.trials), tuple(float(v) for v in u), score))
        return self.stop_at_failure and score < 0

    def initial_design(self, dimension: int, n: int, seed: int) -> bool:
        return any(self.run(u) for u in latin_hypercube(dimension, n, seed))


def adaptive_search(
    evaluate: Callable[[NDArray[np.float64]], float],
    dimension: int,
    budget: int,
    seed: int,
    initial: int = 8,
    sigma: float = 0.25,
    shrink: float = 0.85,
    stop_at_failure: bool = True,
) -> list[Trial]:
    """Look for failures (score < 0) with a falsification search: a Latin hypercube of ``initial`` points, then
    Gaussian steps (σ = ``sigma``, × ``shrink`` a step, clipped to the cube) about the lowest score found so far,
    in the spirit of the cross-entropy / hill-climbing falsifiers of CPS testing. Stops at the first failure
    (``stop_at_failure``) or after ``budget`` evaluations; deterministic for ``seed``."""
    if budget < 1 or initial < 1:
        raise ParameterError("budget", f"expected a budget and an initial design of at least 1 run, got {budget}, {initial}")
    rng = np.random.default_rng(seed)
    log = TrialLog(evaluate, stop_at_failure)
    if log.initial_design(dimension, min(initial, budget), seed):
        return log.trials
    step = sigma
    while len(log.trials) < budget:
        best = min(log.trials, key=lambda t: t.score)
        u = np.clip(np.asarray(best.point) + step * rng.standard_normal(dimension), 0.0, 1.0)
        if log.run(u):
            break
        step = max(step * shrink, 0.02)
    return log.trials
