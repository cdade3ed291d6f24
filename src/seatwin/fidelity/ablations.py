"""Deliberately wrong radar models, each derived from a fitted one: a fidelity score must rank them below it.

Each is a pure function ``RadarConfig → RadarConfig`` that changes one aspect of the model and
leaves the rest (geometry, the other parameters, the fit's report) as fitted; the copy's
``name`` says which ablation it is.
"""

from __future__ import annotations

from collections.abc import Callable

from seatwin.sensors.radar.config import ClutterConfig, RadarConfig

FLAT_PD_SNR_DB = 80.0
"""Reference SNR [dB] that puts every target in the data at the detection cap (Pd = ``pd_max``):
at 2.5 km and a tenth of the reference area the SNR is still ~ 4·10⁵, ``pfa^(1/(1+SNR)) > 0.9999``."""
TOO_CLEAN_SCALE = 1e-3
"""Factor on the fitted range and bearing σ of ``too_clean`` (σ ≈ 0; exactly 0 would be a degenerate model)."""


def _named(config: RadarConfig, ablation: str, **update: object) -> RadarConfig:
    return config.model_copy(update={"name": f"{config.name} ({ablation})", **update})


def no_bias(config: RadarConfig) -> RadarConfig:
    """The bearing bias set to 0 (everything else as ``config``)."""
    return _named(config, "no_bias", noise=config.noise.model_copy(update={"bearing_bias_deg": 0.0}))


def wide_noise(config: RadarConfig, factor: float = 3.0) -> RadarConfig:
    """Range and bearing σ × ``factor`` (biases kept)."""
    n = config.noise
    noise = n.model_copy(update={"range_sigma_m": n.range_sigma_m * factor, "bearing_sigma_deg": n.bearing_sigma_deg * factor})
    return _named(config, "wide_noise", noise=noise)


def flat_pd(config: RadarConfig, pd: float) -> RadarConfig:
    """The detection probability ``pd`` at every range and aspect: cap ``pd_max = pd`` with an SNR so high
    (:data:`FLAT_PD_SNR_DB`) that the radar equation never brings it lower."""
    detection = config.detection.model_copy(update={"pd_max": pd, "snr_ref_db": FLAT_PD_SNR_DB})
    return config.model_copy(update={"detection": detection})


def low_pd(config: RadarConfig, pd: float = 0.3) -> RadarConfig:
    """Detection probability ``pd`` (0.3) everywhere (:func:`flat_pd`)."""
    return _named(flat_pd(config, pd), "low_pd")


def scale_clutter(clutter: ClutterConfig, factor: float) -> ClutterConfig:
    """The clutter density × ``factor``: the uniform density, and every cell of a map (and outside it)."""
    update: dict[str, object] = {"density_per_km2": clutter.density_per_km2 * factor}
    if clutter.map is not None:
        m = clutter.map
        update["map"] = m.model_copy(
            update={"density": [[v * factor for v in row] for row in m.density], "outside_density": m.outside_density * factor}
        )
    return clutter.model_copy(update=update)


def heavy_clutter(config: RadarConfig, factor: float = 10.0) -> RadarConfig:
    """Clutter density × ``factor`` (10)."""
    return _named(config, "heavy_clutter", clutter=scale_clutter(config.clutter, factor))


def too_clean(config: RadarConfig) -> RadarConfig:
    """σ ≈ 0 (range and bearing σ × :data:`TOO_CLEAN_SCALE`), Pd 0.99 everywhere, no clutter (biases kept)."""
    n = config.noise
    noise = n.model_copy(
        update={"range_sigma_m": n.range_sigma_m * TOO_CLEAN_SCALE, "bearing_sigma_deg": n.bearing_sigma_deg * TOO_CLEAN_SCALE}
    )
    clean = flat_pd(config, 0.99)
    return _named(clean, "too_clean", noise=noise, clutter=ClutterConfig(kind="none", density_per_km2=0.0))


ABLATIONS: dict[str, Callable[[RadarConfig], RadarConfig]] = {
    "no_bias": no_bias,
    "wide_noise": wide_noise,
    "low_pd": low_pd,
    "heavy_clutter": heavy_clutter,
    "too_clean": too_clean,
}
"""The wrong models scored beside the fitted one (``seatwin fidelity joyride --ablations``), in report order."""


def ablated_models(fitted: RadarConfig) -> dict[str, RadarConfig]:
    """Every ablation of ``fitted``, by name."""
    return {name: f(fitted) for name, f in ABLATIONS.items()}
