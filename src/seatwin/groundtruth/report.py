"""The JSON quality report: per vessel, how far its ground truth can be trusted."""

from __future__ import annotations

from typing import Any

import numpy as np

from seatwin.groundtruth.vessel import FLAG_NAMES, VesselGroundTruth


def _stats(x: np.ndarray) -> dict[str, float]:
    return {
        "mean": float(np.mean(x)),
        "median": float(np.median(x)),
        "p95": float(np.percentile(x, 95)),
        "max": float(np.max(x)),
    }


def vessel_report(number: int, v: VesselGroundTruth) -> dict[str, Any]:
    """The report entry of vessel ``number`` (1-based, the Gemini CSV column ``V{number}``)."""
    n = len(v.time)
    flagged = v.flags != 0
    entry: dict[str, Any] = {
        "number": number,
        "name": v.name,
        "samples": n,
        "heading_source": v.heading_source,
        "flagged_fraction": float(flagged.mean()),
        "flagged_samples": int(flagged.sum()),
        "flagged_by_reason": {name: int(((v.flags & bit) != 0).sum()) for bit, name in FLAG_NAMES.items()},
        "speed_mps": _stats(np.hypot(v.v_north, v.v_east)),
        "settings": v.settings,
        "antennas": [
            {
                "role": role,
                "file": a.log.source,
                "format": a.log.format,
                "fixes": len(a.log),
                "start_posix": a.log.start,
                "end_posix": a.log.end,
                "median_fix_interval_s": float(np.median(np.diff(a.log.time))),
                "fix_quality_counts": a.log.quality_counts(),
                "resampled_fix_quality_counts": (None if a.quality is None else _named_counts(a.log.quality_scheme, a.quality)),
                "skipped_records": dict(a.log.skipped),
                "samples_across_gaps": int(a.gap.sum()),
            }
            for role, a in zip(("bow", "stern") if len(v.antennas) == 2 else ("single",), v.antennas)
        ],
    }
    if v.eps_gnss is not None:
        entry["baseline_m"] = v.baseline_m
        entry["baseline_source"] = v.baseline_source
        entry["eps_threshold_m"] = v.eps_threshold_m
        entry["eps_gnss_m"] = _stats(v.eps_gnss)
    else:
        entry["eps_gnss_m"] = None
    return entry


def _named_counts(scheme: str | None, codes: np.ndarray) -> dict[str, int]:
    from seatwin.groundtruth.log import quality_name

    u, c = np.unique(codes, return_counts=True)
    return {quality_name(scheme, k): int(m) for k, m in zip(u, c)}


def quality_report(result: Any) -> dict[str, Any]:
    """The whole report for a :class:`~seatwin.groundtruth.pipeline.GroundTruthResult`."""
    o = result.origin
    return {
        "origin": {"lat_deg": o.lat_deg, "lon_deg": o.lon_deg, "height_m": o.height_m},
        "meridian": result.meridian,
        "rate_hz": result.rate_hz,
        "max_gap_s": result.max_gap_s,
        "start_posix": float(result.time[0]),
        "end_posix": float(result.time[-1]),
        "samples": len(result.time),
        "flag_bits": {name: bit for bit, name in FLAG_NAMES.items()},
        "vessels": [vessel_report(i, v) for i, v in enumerate(result.vessels, start=1)],
    }
