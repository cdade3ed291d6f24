"""Run a fidelity sweep: reference runs per seed, degraded copies per (kind, strength, seed), AHED of each pair.

What isolates the degradation: every degraded copy is compared with the reference run of the
*same seed*. Random draws are counter-based (:func:`seatwin.rng.frame_rng`), so the two runs
share every draw (noise, drops) and differ only by the degraded parameter; comparing against
one fixed reference would add the seed-to-seed difference to every point. That difference is
measured separately (references of different seeds against each other, the "seed-to-seed
floor") so a reader sees how large a difference random draws alone make.
"""

from __future__ import annotations

import contextlib
import io
import itertools
import shutil
import tempfile
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from seatwin.errors import InputError
from seatwin.evaluation.compare import CompareOptions, compare, comparison_table
from seatwin.evaluation.tracks_io import Tracks, write_tracks
from seatwin.evaluation.truth import TruthSet, truth_from_scenario
from seatwin.sweep.degradations import Degradation
from seatwin.sweep.results import FLOOR_KIND, REFERENCE_KIND, SweepResult, SweepRow

DEFAULT_TUNING = "synthetic"


@dataclass(frozen=True)
class SweepSettings:
    """What to sweep: scenario (built-in name or file), kinds with their strengths, seeds, window, tuning.

    ``offset`` is the window's start in seconds after the scenario's start (default: the window
    centred in the scenario). AHED is undefined (None) for a target without common instants:
    ``both_missing="skip"``, so that "neither run tracked it" never counts as agreement.
    """

    scenario: str
    kinds: tuple[Degradation, ...]
    strengths: dict[str, tuple[float, ...]] = field(default_factory=dict)
    seeds: tuple[int, ...] = (1, 2, 3)
    duration: float = 30.0
    offset: float | None = None
    tuning: str = DEFAULT_TUNING
    options: CompareOptions = field(default_factory=lambda: CompareOptions(both_missing="skip"))
    keep_recordings: bool = False

    def strengths_of(self, d: Degradation) -> tuple[float, ...]:
        return tuple(self.strengths.get(d.kind, d.default_strengths))

    def n_steps(self) -> int:
        """Simulate-and-track steps: one reference per seed and one copy per (kind, strength, seed)."""
        return len(self.seeds) * (1 + sum(len(self.strengths_of(d)) for d in self.kinds))

    def check(self) -> None:
        if not self.kinds:
            raise InputError("--kinds", "no degradation to sweep")
        if not self.seeds or len(set(self.seeds)) != len(self.seeds):
            raise InputError("--seeds", f"expected distinct seeds, got {self.seeds}")
        if not self.duration > 0:
            raise InputError("--duration", f"must be positive, got {self.duration}")
        for d in self.kinds:
            s = self.strengths_of(d)
            if not s or len(set(s)) != len(s):
                raise InputError("--strengths", f"{d.kind}: expected distinct strengths, got {s}")
            for x in s:
                d.settings(x)

    def describe(self) -> dict:
        return {
            "scenario": self.scenario, "kinds": [d.kind for d in self.kinds],
            "strengths": {d.kind: list(self.strengths_of(d)) for d in self.kinds},
            "references": {d.kind: d.reference for d in self.kinds},
            "units": {d.kind: d.unit for d in self.kinds}, "labels": {d.kind: d.label for d in self.kinds},
            "seeds": list(self.seeds), "duration_s": self.duration, "offset_s": self.offset, "tuning": self.tuning,
            "lidar": "vlp16 preset, exact ray casting",
            "comparison": {"reference": "the seed-matched reference run", "ahed": "mean over targets of AHED (5.34)",
                           "hellinger_form": self.options.form, "both_missing": self.options.both_missing,
                           "gate_m": self.options.gate, "time_tolerance_s": self.options.time_tolerance},
        }


def _track(recording: Path, tuning: str) -> Tracks:
    """Track a recording with ``tuning`` through ``seatwin track`` (quietly)."""
    from seatwin.cli.compare import load_run

    with contextlib.redirect_stdout(io.StringIO()):
        return load_run(str(recording), tuning)


def _row(kind: str, strength: float, seed: int, ref_seed: int, ref: Tracks, other: Tracks, truth: TruthSet,
         settings: SweepSettings) -> SweepRow:
    table = comparison_table([compare(ref, other, truth, settings.tuning, settings.options)])
    lines = table["targets"]
    frac = [ln["fraction_only_one"] for ln in lines if ln["fraction_only_one"] is not None]
    return SweepRow(kind, float(strength), int(seed), int(ref_seed), table["ahed_mean"],
                    int(sum(ln["n_common"] for ln in lines)), float(np.mean(frac)) if frac else None,
                    sum(1 for ln in lines if ln["ahed"] is not None))


def run_sweep(settings: SweepSettings, out_dir: str | Path,
              step: Callable[[str], None] | None = None) -> SweepResult:
    """Run the sweep; track files go to ``out_dir/tracks`` (recordings to ``out_dir/recordings`` if kept).

    ``step(description)`` is called after each simulate-and-track step (for a progress bar).
    """
    from seatwin.scenario.load import load_scenario
    from seatwin.sim import simulate_scenario

    settings.check()
    out_dir = Path(out_dir)
    scenario = load_scenario(settings.scenario)
    span = scenario.end - scenario.start
    offset = settings.offset if settings.offset is not None else max(0.0, (span - settings.duration) / 2)
    if not (0 <= offset and offset + settings.duration <= span + 1e-9):
        raise InputError("--offset", f"the window [{offset:g}, {offset + settings.duration:g}] s is not inside "
                                     f"the scenario's {span:g} s")
    settings = replace(settings, offset=float(offset))
    truth = truth_from_scenario(scenario)
    tracks_dir = out_dir / "tracks"
    if tracks_dir.exists() and any(tracks_dir.iterdir()):
        raise InputError(out_dir, "an earlier sweep is here; remove it or give another --out")
    tracks_dir.mkdir(parents=True, exist_ok=True)
    result = SweepResult(settings.describe())
    step = step or (lambda _: None)

    with tempfile.TemporaryDirectory(prefix="seatwin-sweep-") as tmp:
        rec_root = out_dir / "recordings" if settings.keep_recordings else Path(tmp)

        def run(name: str, seed: int, **kwargs) -> Tracks:  # noqa: ANN003
            rec = rec_root / name
            simulate_scenario(scenario, rec, start=scenario.start + settings.offset, duration=settings.duration, seed=seed,
                              progress=False, **kwargs)
            tracks = _track(rec, settings.tuning)
            write_tracks(tracks_dir / f"{name}.csv", tracks)
            if not settings.keep_recordings:
                shutil.rmtree(rec, ignore_errors=True)
            step(name)
            return tracks

        refs: dict[int, Tracks] = {s: run(f"reference_seed{s}", s) for s in settings.seeds}
        for s in settings.seeds:
            result.rows.append(_row(REFERENCE_KIND, 0.0, s, s, refs[s], refs[s], truth, settings))
        for a, b in itertools.combinations(settings.seeds, 2):
            result.rows.append(_row(FLOOR_KIND, 0.0, b, a, refs[a], refs[b], truth, settings))
        for d in settings.kinds:
            for strength in settings.strengths_of(d):
                for s in settings.seeds:
                    tracks = run(f"{d.kind}_{strength:g}_seed{s}", s, **d.settings(strength))
                    result.rows.append(_row(d.kind, strength, s, s, refs[s], tracks, truth, settings))
    return result


def parse_floats(text: str, what: str) -> tuple[float, ...]:
    """``"0.1,0.2"`` → ``(0.1, 0.2)`` (``InputError`` naming ``what`` otherwise)."""
    try:
        values = tuple(float(p) for p in text.split(",") if p.strip())
    except ValueError:
        raise InputError(what, f"expected comma-separated numbers, got {text!r}") from None
    if not values:
        raise InputError(what, f"expected comma-separated numbers, got {text!r}")
    return values


def parse_strengths(text: str | None, kinds: Sequence[Degradation]) -> dict[str, tuple[float, ...]]:
    """``"noise=0.1,0.2;mount=1,2"`` → per-kind strengths; a bare list applies to a single kind."""
    if not text:
        return {}
    out: dict[str, tuple[float, ...]] = {}
    known = {d.kind for d in kinds}
    for part in (p.strip() for p in text.split(";") if p.strip()):
        if "=" not in part:
            if len(kinds) != 1:
                raise InputError("--strengths", "with several kinds write KIND=S1,S2;KIND=… (e.g. noise=0.1,0.2;mount=1,2)")
            out[kinds[0].kind] = parse_floats(part, "--strengths")
            continue
        kind, values = (x.strip() for x in part.split("=", 1))
        if kind not in known:
            raise InputError("--strengths", f"{kind!r} is not among the swept kinds {sorted(known)}")
        out[kind] = parse_floats(values, "--strengths")
    return out
