"""Every choice of a fidelity run (the options of ``seatwin fidelity joyride``)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, ValidationInfo, field_validator

from seatwin.settings import Settings

FIT_ON = ("none", "first-half", "all")
AGENTS = ("jipda", "gnn")


class FidelityOptions(Settings):
    """How the real recording and its synthetic replicas are made, tracked and compared."""

    tuning: str = Field("joyride", description="Tracker tuning on both datasets (preset or tuning file).")
    fit_on: Literal["none", "first-half", "all"] = Field(
        "none",
        description="Fit the radar model on: none (the default model), first-half (AHED then on the second "
        "half only: no peeking) or all (for reference).",
    )
    seeds: int = Field(5, ge=1, description="Synthetic recordings (seeds) compared with the real one.")
    n_boot: int = Field(1000, ge=1, description="Bootstrap resamples of the AHED interval.")
    block: int = Field(
        10,
        ge=1,
        description="Bootstrap block length [instants] of the AHED interval (HED is autocorrelated over a few scans); the "
        "score's blocks are chosen from the data.",
    )
    fit_boot: int = Field(200, ge=0, description="Bootstrap resamples of the radar fit.")
    fit_by: Literal["moments", "score"] = Field(
        "moments",
        description="How the radar model is fitted: moments (plot statistics about the truth: seatwin.sensors.radar.fit) "
        "or score (then matched to the real plots in the radar sensor score's own statistics by simulation: "
        "seatwin.fidelity.radar_fit.fit_by_score, so the fit and the score agree; ~8 replica runs more).",
    )
    radar: str | None = Field(None, description="Radar YAML to start from (default: the built-in default model).")
    clutter: Literal["uniform", "map"] = Field("uniform", description="Clutter form of the fit.")
    agents: tuple[Literal["jipda", "gnn"], ...] = Field(
        AGENTS, min_length=1, description="Trackers, both with the same EKF and tuning (the first is the headline)."
    )
    seed0: int = Field(0, description="First seed (seeds are seed0 … seed0 + seeds − 1).")
    calibrate_bias: bool = Field(
        False,
        description="Set the tuning's radar bearing_bias to the fitted bearing bias (both datasets, every "
        "model; estimated on the fit's scans only, so no peeking with first-half).",
    )
    untruthed_vessels: bool = Field(
        True,
        description="Add to the replica the vessels without ground truth that the real tracker follows away from the "
        "target (from the real tracks: seatwin.fidelity.joyride.untruthed_vessels); the radar models are compared "
        "on the same scene as reality, not on a scene missing a boat.",
    )
    dont_care: bool = Field(
        True,
        description="Leave the plots and confirmed tracks near the un-truthed vessels out of the score's clutter and "
        "false-track terms, in both datasets (docs/fidelity-score.md, Don't-care vessels); off: they count as clutter "
        "and false tracks. The vessels stay in the replica either way.",
    )
    ablations: bool = Field(
        False,
        description="Also score deliberately wrong radar models derived from the fitted one (no_bias, wide_noise, "
        "low_pd, heavy_clutter, too_clean: seatwin.fidelity.ablations); the fitted model should rank first.",
    )

    @field_validator("agents")
    @classmethod
    def _distinct(cls, v: tuple[str, ...]) -> tuple[str, ...]:
        if len(set(v)) != len(v):
            raise ValueError("an agent is repeated")
        return v

    @field_validator("calibrate_bias", "ablations")
    @classmethod
    def _needs_fit(cls, v: bool, info: ValidationInfo) -> bool:
        if v and info.data.get("fit_on") == "none":
            raise ValueError("needs a fitted radar model: fit_on 'first-half' or 'all'")
        return v
