"""Compare a real and a synthetic dataset through the tracker (thesis 5.2): the use-case behind ``seatwin compare``.

Each side is a track file or a recording (tracked with each tuning by :func:`track_recording`);
both are associated with the same ground truth and compared per target (HED, COVDIFF, AHED).
Recordings with lidar and cameras on both sides are also compared with lidar alone and with
lidar + camera, and box by box (:mod:`seatwin.pipeline.camera_compare`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from seatwin.errors import InputError, ParameterError
from seatwin.pipeline.evaluate import check_overlap
from seatwin.pipeline.track import default_sensors, moored_vessels, recording_mask, recording_moored_boats, track_recording

if TYPE_CHECKING:
    from seatwin.evaluation import CompareOptions, Comparison, Tracks, TruthSet

TRACK_FILE_SUFFIXES = (".csv",)


def is_track_file(spec: str | Path) -> bool:
    return Path(spec).suffix.lower() in TRACK_FILE_SUFFIXES


def load_run(spec: str | Path, tuning: str | None = None, **track: Any) -> Tracks:
    """A track file as it is, or a recording tracked with ``tuning`` (its own default when None);
    ``track``: further :class:`~seatwin.pipeline.track.TrackOptions` fields (``sensors``, ``detector``…).
    """
    from seatwin.evaluation import read_tracks

    path = Path(spec)
    if is_track_file(path):
        return read_tracks(path)
    if not path.exists():
        raise InputError(path, "no such track file (.csv) or recording")
    tracks = track_recording(path, tuning=tuning, **track).tracks
    tracks.source = f"{path} (tracked, tuning {tuning or 'the recording default'})"
    return tracks


def default_sensors_of(spec: str | Path) -> tuple[str, ...]:
    """The sensors a recording is tracked with by default (:func:`~seatwin.pipeline.track.default_sensors`);
    () for a track file."""
    from seatwin.recording import open_bag

    if is_track_file(spec) or not Path(spec).exists():
        return ()
    with open_bag(Path(spec)) as rec:
        return default_sensors(rec)


def comparison_pairs(
    real: Sequence[str], synthetic: Sequence[str], tunings: Sequence[str]
) -> list[tuple[str, str, str | None, str]]:
    """(real, synthetic, tuning, label) per comparison; track files are used as given, recordings tracked per tuning."""
    if len(real) != len(synthetic):
        raise ParameterError("real", f"give as many real as synthetic datasets, got {len(real)} and {len(synthetic)}")
    if not real:
        raise ParameterError("real", "give at least one real and one synthetic dataset")
    files = [is_track_file(p) for p in [*real, *synthetic]]
    if len(real) == 1 and len(tunings) > 1:
        if any(files):
            raise ParameterError(
                "tunings",
                f"{len(tunings)} tunings but a track file was already tracked with one "
                "tuning; give one real/synthetic pair per tuning, or recordings",
            )
        return [(real[0], synthetic[0], t, t) for t in tunings]
    if tunings and len(tunings) != len(real):
        raise ParameterError("tunings", f"{len(tunings)} tunings for {len(real)} real/synthetic pairs")
    if tunings:
        return [(r, s, t, t) for r, s, t in zip(real, synthetic, tunings, strict=True)]
    labels = [""] if len(real) == 1 else [f"pair{i + 1}" for i in range(len(real))]
    return [(r, s, None, label) for r, s, label in zip(real, synthetic, labels, strict=True)]


def _manifest(spec: str | Path) -> dict[str, Any] | None:
    from seatwin.recording.manifest import read_manifest

    path = Path(spec)
    return read_manifest(path) if path.is_dir() else None


def scenario_name(truth: str | Path) -> str:
    """The scenario's own name: from a recording's manifest, a scenario file or a built-in name."""
    manifest = _manifest(truth)
    name = ((manifest or {}).get("metadata") or {}).get("scenario") if manifest else None
    if name:
        return str(name)
    if not Path(truth).exists():
        return str(truth)  # a built-in scenario's name
    return Path(truth).stem


def describe_dataset(spec: str | Path) -> str:
    """What a dataset is, for the report: a track file, an imported real recording, or one seatwin simulated."""
    if is_track_file(spec):
        return f"track file {Path(spec).name}"
    manifest = _manifest(spec)
    settings = ((manifest or {}).get("metadata") or {}).get("settings")
    if settings:
        sensors = ", ".join(settings.get("sensors", []))
        extra = [f"{k} {settings[k]}" for k in ("lidar_mode", "range_noise", "ray_drop") if settings.get(k) is not None]
        extra += [k for k in ("dissipation",) if settings.get(k)]
        return f"simulated by seatwin ({sensors}; {', '.join(extra)}; seed {manifest.get('seed')})"
    return f"recording {Path(spec).name}"


def shared_draws(real: str | Path, synthetic: str | Path) -> str | None:
    """Why ``real`` and ``synthetic`` are not independent, or None: two recordings seatwin simulated from the same
    scenario with the same seed share their random draws (noise, drops, clutter), so their distance understates
    any real-versus-synthetic difference (docs/fidelity-score.md); with the same settings too they are the same run."""
    runs = [_manifest(p) for p in (real, synthetic)]
    meta = [(m or {}).get("metadata") or {} for m in runs]
    if not all(m.get("settings") for m in meta) or any(m is None for m in runs):
        return None  # a track file, an imported recording: its draws are its own
    seeds = [m.get("seed") for m in runs]  # type: ignore[union-attr]  # both manifests are present (checked above)
    if seeds[0] is None or seeds[0] != seeds[1] or meta[0].get("scenario") != meta[1].get("scenario"):
        return None
    what = f"both runs were simulated from {meta[0].get('scenario')} with seed {seeds[0]}"
    if meta[0]["settings"] == meta[1]["settings"] and meta[0].get("start") == meta[1].get("start"):
        return f"{what} and the same settings: they are the same run, so every distance is zero or sampling noise"
    return f"{what}: they share their random draws, so their distance understates the difference; use different seeds"


@dataclass
class CompareResult:
    """The comparisons (one per tuning or pair), their table, and what was written."""

    real: list[str]
    synthetic: list[str]
    truth: str
    comparisons: list[Comparison]
    table: dict[str, Any]
    report: Path | None = None
    track_files: list[Path] = field(default_factory=list)
    camera: dict[str, Any] | None = None
    """Lidar against lidar + camera AHED and the box comparison (:func:`camera_comparison`); None without cameras."""
    dont_care: dict[str, Any] | None = None
    """The vessels the score left out as don't-care regions, and their source; None when none were given."""
    warnings: list[str] = field(default_factory=list)
    """What makes the comparison weaker than it looks (:func:`shared_draws`); shown on the console and in the report."""

    def to_json(self) -> dict[str, Any]:
        """The JSON of ``seatwin compare --json``."""
        extra = {} if self.camera is None else {"camera": self.camera}
        if self.dont_care is not None:
            extra["dont_care"] = self.dont_care
        if self.warnings:
            extra["warnings"] = self.warnings
        return {"real": self.real, "synthetic": self.synthetic, "truth": self.truth, **self.table, **extra}


def _clouds(real: str, synthetic: str, when: float, sensor: str, truth: TruthSet, relative: bool):  # noqa: ANN202
    """Fig. 5.10 input: both recordings' clouds nearest ``when`` (POSIX, or seconds after the truth's start)."""
    from seatwin.report import Clouds
    from seatwin.report.clouds import cloud_at

    for spec in (real, synthetic):
        if is_track_file(spec):
            raise ParameterError("clouds_at", f"{spec} is a track file; point clouds need recordings on both sides")
    t = when + (min(tr.start for tr in truth.targets.values()) if relative else 0.0)
    r, s = cloud_at(real, t, sensor), cloud_at(synthetic, t, sensor)
    return Clouds(r.time, r.points, s.points, r.ownship, r.targets)


def dont_care_vessels(source: str | Path, truth: TruthSet) -> TruthSet:
    """The vessels of ``source`` (anything :func:`seatwin.evaluation.load_truth` reads) that are not targets of
    ``truth``: the score's don't-care regions. A source whose vessels are all targets is refused."""
    from seatwin.evaluation import TruthSet, load_truth

    vessels = load_truth(source)
    extra = {name: track for name, track in vessels.targets.items() if name not in truth.targets}
    if not extra:
        raise InputError(
            source, f"no vessel here beyond the ground truth's targets ({', '.join(truth.names)}): nothing to leave out"
        )
    return TruthSet(extra, str(source))


def compare_runs(
    real: Sequence[str | Path],
    synthetic: Sequence[str | Path],
    truth: str | Path,
    *,
    tunings: Sequence[str] = (),
    options: CompareOptions | None = None,
    report_dir: Path | None = None,
    report_map: str = "harbour",
    clouds_at: float | None = None,
    clouds_relative: bool = False,
    clouds_sensor: str = "lidar",
    keep_tracks: Path | None = None,
    camera_fusion: bool = True,
    detector: str = "label",
    model: str | None = None,
    box_min_iou: float | None = None,
    dont_care: str | Path | None = None,
) -> CompareResult:
    """Compare each real/synthetic pair against ``truth`` (scenario or recording), per tuning.

    ``report_dir``: also write the HTML report there (land of ``report_map`` under the plots;
    both datasets' clouds at ``clouds_at`` when given). ``keep_tracks``: write the track files
    of tracked recordings into this folder. ``camera_fusion``: where both recordings of a pair
    have lidar and cameras, also compare lidar alone against lidar + camera with the camera
    ``detector`` (``label``, or ``onnx`` with ``model``) and their boxes (matched at IoU ≥ ``box_min_iou``, default
    :data:`~seatwin.evaluation.boxes.DEFAULT_MIN_IOU`). ``dont_care``: a scenario, truth file or recording with
    vessels that have no reliable ground truth (e.g. AIS tracks); its vessels that are not targets of ``truth``
    are neither clutter nor false tracks in the fidelity score (:func:`dont_care_vessels`).
    """
    from seatwin.evaluation import CompareOptions, TruthSet, compare, comparison_table, load_truth, write_tracks
    from seatwin.evaluation.boxes import DEFAULT_MIN_IOU
    from seatwin.perception.camera_frames import camera_detector

    options = options or CompareOptions()
    real, synthetic = [str(p) for p in real], [str(p) for p in synthetic]
    camera_cfg = camera_detector(detector, model)
    min_iou = DEFAULT_MIN_IOU if box_min_iou is None else box_min_iou
    if not 0.0 < min_iou <= 1.0:
        raise ParameterError("box_min_iou", f"expected 0 < IoU <= 1, got {min_iou}")
    if clouds_at is not None and report_dir is None:
        raise ParameterError("clouds_at", "the point clouds go into the report: give a report folder as well")
    if clouds_sensor not in ("lidar", "radar"):
        raise ParameterError("clouds_sensor", f"expected 'lidar' or 'radar', got {clouds_sensor!r}")
    pairs = comparison_pairs(real, synthetic, list(tunings))
    truth_set = load_truth(truth)
    ignored = None if dont_care is None else dont_care_vessels(dont_care, truth_set)
    mask = recording_mask(truth)
    moored = moored_vessels(recording_moored_boats(truth), truth_set)
    if moored is not None:  # the harbour's moored boats: real, no ground truth
        ignored = moored if ignored is None else TruthSet({**ignored.targets, **moored.targets}, ignored.source)
    cache: dict[tuple[str, str | None, tuple[str, ...]], Tracks] = {}
    written: set[tuple[str, str | None, tuple[str, ...]]] = set()
    kept: list[Path] = []

    def run_of(spec: str, tuning: str | None, side: str, sensors: tuple[str, ...] = ()) -> Tracks:
        """Tracks of ``spec``: a recording is tracked once per tuning and sensors (() its default sensors, so
        that asking for them by name — lidar alone beside lidar + camera — reuses the same tracks); with
        ``keep_tracks``, each (recording, tuning, sensors asked for) is written once, named by the side asking first."""
        key = (spec, tuning, sensors or default_sensors_of(spec))
        if key not in cache:
            track: dict[str, Any] = {"sensors": sensors} if sensors else {}
            if "camera" in sensors and camera_cfg is not None:
                track.update(detector=detector, model=model)
            cache[key] = load_run(spec, tuning, **track)
        if keep_tracks is not None and not is_track_file(spec) and (spec, tuning, sensors) not in written:
            written.add((spec, tuning, sensors))
            suffix = "".join(f"_{s}" for s in sensors)
            keep = Path(keep_tracks) / f"{side}_{Path(spec).stem}_{tuning or 'default'}{suffix}.csv"
            keep.parent.mkdir(parents=True, exist_ok=True)
            write_tracks(keep, cache[key])
            kept.append(keep)
        return cache[key]

    comparisons = []
    for r, s, t, label in pairs:
        run_r, run_s = run_of(r, t, "real"), run_of(s, t, "synthetic")
        check_overlap(run_r, truth_set, r)
        check_overlap(run_s, truth_set, s)
        comparisons.append(compare(run_r, run_s, truth_set, tuning=label, options=options, mask=mask, dont_care=ignored))
    camera = None
    recordings = [p for p in pairs if not is_track_file(p[0]) and not is_track_file(p[1])]
    if camera_fusion and recordings:
        from seatwin.pipeline.camera_compare import camera_comparison

        camera = camera_comparison(recordings, truth_set, options, mask, camera_cfg, run_of, min_iou)
    result = CompareResult(
        real, synthetic, str(truth), comparisons, comparison_table(comparisons), track_files=kept, camera=camera
    )
    if ignored is not None:
        source = str(dont_care) if dont_care is not None else "the moored boats of the harbour"
        result.dont_care = {"source": source, "vessels": ignored.names}
    result.warnings = list(dict.fromkeys(w for r, s, _, _ in pairs if (w := shared_draws(r, s)) is not None))
    if report_dir is not None:
        from seatwin.perception.map_mask import load_mask
        from seatwin.report import write_comparison_report

        clouds = (
            [] if clouds_at is None else [_clouds(real[0], synthetic[0], clouds_at, clouds_sensor, truth_set, clouds_relative)]
        )
        name = scenario_name(truth)
        described = [(describe_dataset(r), describe_dataset(s)) for r, s, _, _ in pairs]
        notes = list(dict.fromkeys(f"“Real” dataset: {r}. “Synthetic” dataset: {s}." for r, s in described))  # once per pair
        if any(r.startswith("simulated") for r, _ in described):
            notes.append("The “real” side here is itself simulated: this compares two sensor models, not reality.")
        notes += [f"Warning: {w}." for w in result.warnings]
        result.report = write_comparison_report(
            report_dir,
            comparisons,
            truth_set,
            title=f"seatwin compare — {name}",
            scenario=name,
            mask=load_mask(report_map),
            clouds=clouds,
            notes=notes,
            camera=camera,
        )
    return result
