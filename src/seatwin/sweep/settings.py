"""What a fidelity sweep varies: the scenario, the degradations and their strengths, seeds, window, tuning."""

from __future__ import annotations

from typing import Any

from pydantic import Field, ValidationInfo, field_validator

from seatwin.errors import ParameterError
from seatwin.evaluation.compare import CompareOptions
from seatwin.settings import Seeds, Settings
from seatwin.sweep.degradations import DEGRADATIONS, Degradation, degradation, degradations, reference_model

DEFAULT_TUNING = "synthetic"


class SweepSettings(Settings):
    """Every choice of a sweep. AHED is undefined (None) for a target without common instants
    (``both_missing="skip"``), so that "neither run tracked it" never counts as agreement."""

    scenario: str = Field("ferry_crossing", description="Built-in scenario name or scenario file.")
    kinds: tuple[str, ...] = Field(
        tuple(DEGRADATIONS), description=f"Degradations to sweep, in this order; some of {', '.join(DEGRADATIONS)}."
    )
    strengths: dict[str, tuple[float, ...]] = Field(
        default_factory=dict,
        description="Strengths per kind, in the kind's unit, each beyond the reference model or, where the kind "
        "allows, cleaner than it (default: the kind's default strengths).",
    )
    seeds: Seeds = Field((1, 2, 3), min_length=1, description="Distinct seeds: every point is repeated with each.")
    duration: float = Field(
        60.0, gt=0, description="Simulated seconds per run (the score's sampling floor shrinks with more instants)."
    )
    offset: float | None = Field(
        None,
        ge=0,
        description="Window start in seconds after the scenario's start (default: the window centred in the scenario).",
    )
    tuning: str = Field(DEFAULT_TUNING, description="Tracker tuning of every run (preset or tuning file).")
    reference_seed_offset: int = Field(
        1000,
        ge=0,
        description="The reference run of seed s uses seed s + this (0: seed-matched, sharing every draw — "
        "which no real-versus-synthetic comparison can).",
    )
    comparison: CompareOptions = Field(
        default_factory=lambda: CompareOptions(both_missing="skip"),
        description="Conventions of each comparison with the reference run.",
    )

    @field_validator("kinds")
    @classmethod
    def _known_kinds(cls, v: tuple[str, ...]) -> tuple[str, ...]:
        try:
            degradations(v)
        except ParameterError as exc:
            raise ValueError(exc.detail) from None
        return v

    @field_validator("strengths")
    @classmethod
    def _valid_strengths(cls, v: dict[str, tuple[float, ...]], info: ValidationInfo) -> dict[str, tuple[float, ...]]:
        kinds = info.data.get("kinds", ())
        for kind, values in v.items():
            if kind not in kinds:
                raise ValueError(f"{kind!r} is not among the swept kinds {list(kinds)}")
            if not values or len(set(values)) != len(values):
                raise ValueError(f"{kind}: expected distinct strengths")
            for x in values:
                problem = degradation(kind).strength_problem(x)
                if problem is not None:
                    raise ValueError(problem)
        return v

    @property
    def degradations(self) -> list[Degradation]:
        return degradations(self.kinds)

    def strengths_of(self, d: Degradation) -> tuple[float, ...]:
        return tuple(self.strengths.get(d.kind, d.default_strengths))

    def n_steps(self) -> int:
        """Simulate-and-track jobs: per seed a reference run, the reference model and one copy per (kind, strength)."""
        return len(self.seeds) * (2 + sum(len(self.strengths_of(d)) for d in self.degradations))

    def window_offset(self, span: float) -> float:
        """The window's start [s after the scenario's start] in a scenario of ``span`` seconds (checked; the
        campaign's rule: :func:`seatwin.campaign.grid.window_offset`)."""
        from seatwin.campaign.grid import window_offset

        return window_offset(span, self.duration, self.offset, self.scenario)

    def describe(self) -> dict[str, Any]:
        """The settings as ``sweep.json`` records them."""
        ds, c = self.degradations, self.comparison
        return {
            "scenario": self.scenario,
            "kinds": list(self.kinds),
            "strengths": {d.kind: list(self.strengths_of(d)) for d in ds},
            "references": {d.kind: d.reference for d in ds},
            "units": {d.kind: d.unit for d in ds},
            "labels": {d.kind: d.label for d in ds},
            "seeds": list(self.seeds),
            "duration_s": self.duration,
            "offset_s": self.offset,
            "tuning": self.tuning,
            "lidar": "vlp16 preset, exact ray casting",
            "reference_model": reference_model(),
            "reference_seed_offset": self.reference_seed_offset,
            "comparison": {
                "reference": "the seed-matched reference run"
                if self.reference_seed_offset == 0
                else f"the reference run of seed s + {self.reference_seed_offset}",
                "score": "overall fidelity score (S5, docs/fidelity-score.md)",
                "ahed": "mean over targets of AHED (5.34)",
                "hellinger_form": c.form,
                "both_missing": c.both_missing,
                "gate_m": c.gate,
                "time_tolerance_s": c.time_tolerance,
            },
        }
