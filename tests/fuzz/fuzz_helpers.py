"""Mutation fuzzing of every seatwin reader: valid seed files, mutations, and the readers' contract.

The contract: a reader given any bytes either returns or raises :class:`seatwin.errors.InputError`;
nothing else escapes. A *target* is one reader with its seed file; the seed lives in a folder of
its own with the files it needs beside it (the CSV a scenario YAML names, the storage file a
rosbag2 ``metadata.yaml`` describes), so a mutant is that folder with one file replaced.

Mutations are plain tuples ``(kind, position, argument)`` so that hypothesis, the measuring
script (``measure_escapes.py``) and the regression corpus share them:

* bytes: ``flip`` (xor a bit), ``truncate``, ``insert`` junk, ``overwrite`` with an absurd
  length/number (``0xFFFFFFFF``, ``0x7FFFFFFF``, …), ``delete`` and ``duplicate`` a range;
* text: ``number`` (a numeric token → ``nan``, ``inf``, ``1e400``, a 400-digit number, …),
  ``utf8`` (invalid UTF-8), ``huge`` (a field beyond csv's 128 KiB limit, or an unclosed quote),
  ``swap_lines``, ``dup_line``, ``drop_line``;
* families of :data:`FAMILY_KINDS`, measured one at a time (``measure_escapes.py --kinds``):
  YAML ``yaml_alias`` (an alias bomb or an anchor/alias pair), ``yaml_deep`` (a value nested
  50–5,000 deep), ``yaml_int`` (a 20–5,000-digit integer), ``nonfinite`` (a number → ``.inf``,
  ``.nan``, ``nan``, ``-inf``, ``1.0e+999``), ``nbsp`` (a no-break space after a number),
  ``udigit`` (a digit → an Arabic-Indic digit ``float()`` would take).
"""

from __future__ import annotations

import gzip
import random
import re
import shutil
import struct
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from seatwin.errors import InputError

Mutation = tuple[str, int, int]

BINARY_KINDS = ("flip", "truncate", "insert", "overwrite", "delete", "duplicate")
TEXT_KINDS = ("number", "utf8", "huge", "swap_lines", "dup_line", "drop_line")
ABSURD = [
    struct.pack("<I", 0xFFFFFFFF),
    struct.pack("<I", 0x7FFFFFFF),
    struct.pack("<I", 0x80000000),
    struct.pack("<I", 0x04000000),
    struct.pack("<Q", 0xFFFFFFFFFFFFFFFF),
    struct.pack("<Q", 0x0000000100000000),
    b"\x00\x00\x00\x00",
    b"\xff",
]
JUNK = [b"\x00", b"\xff\xfe\xfd", b"#ROSBAG V2.0\n", b"\x89MCAP0\r\n", b"\n\n\n", b",,,", b"<", b'"', b"%", b"$GPGGA,"]
NUMBERS = [b"nan", b"inf", b"-inf", b"1e400", b"1e308", b"-1e308", b"0", b"-0", b"", b"9" * 400, b"0x10", b"1_0", b"1e-320"]
FAMILY_KINDS = ("yaml_alias", "yaml_deep", "yaml_int", "nonfinite", "nbsp", "udigit")
BOMB = (
    b'lol: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]\nb: &b [*a,*a,*a,*a,*a,*a,*a,*a,*a]\n'
    b"c: &c [*b,*b,*b,*b,*b,*b,*b,*b,*b]\nd: &d [*c,*c,*c,*c,*c,*c,*c,*c,*c]\ne: &e [*d,*d,*d,*d,*d,*d,*d,*d,*d]\n"
    b"f: &f [*e,*e,*e,*e,*e,*e,*e,*e,*e]\ng: &g [*f,*f,*f,*f,*f,*f,*f,*f,*f]\nh: &h [*g,*g,*g,*g,*g,*g,*g,*g,*g]\n"
)
NONFINITE = [b".inf", b"-.Inf", b".nan", b".NaN", b"nan", b"-inf", b"Infinity", b"1.0e+999", b"-1.0e+999"]
BAD_UTF8 = [b"\xff", b"\xc3\x28", b"\xed\xa0\x80", b"\xe2\x82", b"\x80\x80"]
_NUMBER = re.compile(rb"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")


def apply(data: bytes, mutations: list[Mutation]) -> bytes:
    """``data`` with each mutation applied in turn (positions taken modulo the current length)."""
    for kind, pos, arg in mutations:
        n = len(data)
        p = pos % (n + 1)
        if kind == "flip" and n:
            p %= n
            data = data[:p] + bytes([data[p] ^ (1 << (arg % 8))]) + data[p + 1 :]
        elif kind == "truncate":
            data = data[:p]
        elif kind == "insert":
            data = data[:p] + JUNK[arg % len(JUNK)] + data[p:]
        elif kind == "overwrite":
            junk = ABSURD[arg % len(ABSURD)]
            data = data[:p] + junk + data[p + len(junk) :]
        elif kind == "delete":
            data = data[:p] + data[p + 1 + arg % 64 :]
        elif kind == "duplicate":
            data = data[:p] + data[p : p + 1 + arg % 256] + data[p:]
        elif kind == "number":
            hits = list(_NUMBER.finditer(data))
            if hits:
                m = hits[pos % len(hits)]
                data = data[: m.start()] + NUMBERS[arg % len(NUMBERS)] + data[m.end() :]
        elif kind == "utf8":
            data = data[:p] + BAD_UTF8[arg % len(BAD_UTF8)] + data[p:]
        elif kind == "huge":
            data = data[:p] + (b'"' if arg % 2 else b"x" * 140_000) + data[p:]
        elif kind in FAMILY_KINDS:
            data = _apply_family(data, kind, pos, arg)
        elif kind in ("swap_lines", "dup_line", "drop_line"):
            lines = data.split(b"\n")
            i, j = pos % len(lines), arg % len(lines)
            if kind == "swap_lines":
                lines[i], lines[j] = lines[j], lines[i]
            elif kind == "dup_line":
                lines.insert(i, lines[i])
            elif len(lines) > 1:
                del lines[i]
            data = b"\n".join(lines)
    return data


def _apply_family(data: bytes, kind: str, pos: int, arg: int) -> bytes:
    hits = list(_NUMBER.finditer(data))
    m = hits[pos % len(hits)] if hits else None
    if kind == "yaml_alias":
        lines = data.split(b"\n")
        i = pos % len(lines)
        if arg % 2:  # the bomb, as top-level keys or (mis)placed anywhere
            lines.insert(i, BOMB.rstrip(b"\n"))
        else:  # an anchor on one value and an alias to it in another
            j = (i + 1 + arg % 7) % len(lines)
            lines[i] = re.sub(rb":( +)(\S)", rb":\1&x \2", lines[i], count=1)
            lines[j] = re.sub(rb":( +)\S.*$", rb": *x", lines[j], count=1)
        return b"\n".join(lines)
    if kind == "yaml_deep":
        depth = (50, 65, 200, 1000, 5000)[arg % 5]
        value = b"[" * depth + b"]" * depth if arg % 2 else b"{a: " * depth + b"1" + b"}" * depth
        return data[: m.start()] + value + data[m.end() :] if m else value + data
    if m is None:
        return data
    if kind == "yaml_int":
        value = b"9" * (20, 64, 400, 4300, 5000)[arg % 5]
    elif kind == "nonfinite":
        value = NONFINITE[arg % len(NONFINITE)]
    elif kind == "nbsp":
        value = m.group() + "\u00a0".encode()
    else:  # udigit
        digits = [i for i, c in enumerate(m.group()) if 48 <= c <= 57]
        i = digits[arg % len(digits)]
        value = m.group()[:i] + "\u0663".encode() + m.group()[i + 1 :]
    return data[: m.start()] + value + data[m.end() :]


def random_mutations(rng: random.Random, text: bool, kinds: tuple[str, ...] | None = None) -> list[Mutation]:
    """1–3 random mutations (the measuring script's counterpart of the hypothesis strategy); ``kinds``
    chooses among the given kinds only (a family of :data:`FAMILY_KINDS`, say)."""
    kinds = kinds or BINARY_KINDS + (TEXT_KINDS if text else ())
    return [(rng.choice(kinds), rng.randrange(1 << 30), rng.randrange(1 << 16)) for _ in range(rng.randint(1, 3))]


# ----------------------------------------------------------------------------- readers
def read_bag(path: Path) -> None:
    """Everything a user can ask of a recording: topics, every message, clouds, transforms, truth."""
    from seatwin.recording import open_bag

    target = path.parent if path.name == "metadata.yaml" else path
    with open_bag(target) as rec:
        _ = rec.duration_s, rec.complete, rec.topics
        for _m in rec.messages():
            pass
        for _c in rec.point_clouds():
            _c.xyz()
        list(rec.radar_scans())
        list(rec.images())
        rec.static_transforms()
        rec.ground_truth()


def read_campaign(path: Path) -> None:
    from seatwin.campaign.spec import load_campaign

    load_campaign(path)


def read_scenario(path: Path) -> None:
    from seatwin.scenario.load import load_scenario

    load_scenario(path)


def read_tracks(path: Path) -> None:
    from seatwin.evaluation.tracks_io import read_tracks as read

    read(path)


def read_gnss(path: Path) -> None:
    from seatwin.groundtruth.detect import read_antenna_log

    read_antenna_log(path)


def read_radar_csv(path: Path) -> None:
    from seatwin.perception.datasets import read_ravnkloa_radar

    read_ravnkloa_radar(path)


def read_joyride(path: Path) -> None:
    from seatwin.perception.datasets import read_joyride as read

    read(path)


@dataclass(frozen=True)
class Target:
    name: str
    read: Callable[[Path], object]
    text: bool


TARGETS: dict[str, Target] = {
    t.name: t
    for t in (
        Target("ros1", read_bag, False),
        Target("mcap", read_bag, False),
        Target("sqlite3", read_bag, False),
        Target("rosbag2_yaml", read_bag, True),
        Target("scenario_csv", read_scenario, True),
        Target("scenario_yaml", read_scenario, True),
        Target("campaign_yaml", read_campaign, True),
        Target("tracks", read_tracks, True),
        Target("gpx", read_gnss, True),
        Target("nmea", read_gnss, True),
        Target("rtklib", read_gnss, True),
        Target("gnss_csv", read_gnss, True),
        Target("radar_csv", read_radar_csv, True),
        Target("joyride", read_joyride, False),
    )
}


class MultiLineError(Exception):
    """An InputError whose message is not one line (the CLI promises one)."""


def escape(target: str, path: Path, refused: list[InputError] | None = None) -> BaseException | None:
    """The exception other than InputError that reading ``path`` lets escape (a
    :class:`MultiLineError` for an InputError message of several lines), or None; an InputError
    (the file refused) is appended to ``refused`` when given."""
    return outcome(target, path, refused)[0]


def outcome(target: str, path: Path, refused: list[InputError] | None = None) -> tuple[BaseException | None, bool]:
    """(what :func:`escape` returns, whether ``path`` was read without any error)."""
    try:
        TARGETS[target].read(path)
    except InputError as exc:
        if refused is not None:
            refused.append(exc)
        if "\n" in str(exc) or "\r" in str(exc):
            try:
                raise MultiLineError(str(exc)) from exc
            except MultiLineError as wrapped:
                return wrapped, False
        return None, False
    except Exception as exc:  # noqa: BLE001 - this is what the fuzz tests look for
        return exc, False
    return None, True


def materialize(seed: Path, data: bytes, dest: Path) -> Path:
    """A copy of the seed's folder in ``dest`` with the seed file's bytes replaced by ``data``."""
    if dest.exists():
        shutil.rmtree(dest)
    shutil.copytree(seed.parent, dest)
    out = dest / seed.name
    out.write_bytes(data)
    for extra in dest.glob(seed.name + "-*"):  # e.g. a SQLite journal left by an earlier read
        extra.unlink()
    return out


# ----------------------------------------------------------------------------- the corpus
CORPUS = Path(__file__).parent / "corpus"


def corpus_cases() -> list[Path]:
    """Regression files: ``<target>__<what>.gz`` (gzip of the mutated file)."""
    return sorted(CORPUS.glob("*.gz"))


def corpus_bytes(case: Path) -> tuple[str, bytes]:
    return case.name.split("__", 1)[0], gzip.decompress(case.read_bytes())


def save_case(target: str, tag: str, data: bytes) -> Path:
    CORPUS.mkdir(exist_ok=True)
    out = CORPUS / f"{target}__{tag}.gz"
    out.write_bytes(gzip.compress(data, mtime=0))
    return out


# ----------------------------------------------------------------------------- seeds
def _own_dir(root: Path, name: str) -> Path:
    d = root / name
    d.mkdir(parents=True, exist_ok=True)
    return d


def make_seeds(root: Path) -> dict[str, Path]:
    """Valid seed files of every target under ``root``: bags simulated from a built-in scenario
    (1 s, radar only, ground truth at 2 Hz) in all three formats, the track file the tracker
    writes for one of them, a short Gemini CSV with its YAML, GNSS logs of every format
    (``gt_synth``), a Ravnkloa radar CSV and a joyride ``.mat``."""
    import gt_synth
    from scipy.io import savemat

    from seatwin.evaluation.tracks_io import write_tracks
    from seatwin.pipeline import simulate_run, track_recording
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.scenario.gemini_csv import write_gemini_csv

    seeds: dict[str, Path] = {}
    runs = root / "runs"
    for fmt, name in (("ros1", "recording.bag"), ("mcap", "recording.mcap"), ("sqlite3", "recording.db3")):
        run = runs / fmt
        # uncompressed chunks, as before zstd/lz4 became the defaults: the families mutate the records inside them (the
        # bomb family writes compressed chunks itself)
        simulate_run(
            "ferry_crossing",
            run,
            sensors=("radar",),
            fmt=fmt,
            duration=1.0,
            progress=False,
            ground_truth_rate_hz=2.0,
            compression="none",
        )
        src = next(run.rglob(name))
        seeds[fmt] = shutil.copy(src, _own_dir(root, fmt) / name)
        if fmt == "mcap":
            seeds["rosbag2_yaml"] = shutil.copytree(src.parent, root / "rosbag2_yaml") / "metadata.yaml"
            tracks = track_recording(run).tracks
            write_tracks(_own_dir(root, "tracks") / "TRACKS.csv", tracks)
            seeds["tracks"] = root / "tracks" / "TRACKS.csv"

    sc = builtin_scenario("ferry_crossing")
    time = sc.start + np.arange(0.0, 20.0, 0.5)
    own = next(v for v in sc.vessels if v.role.value == "ownship")
    others = [v for v in sc.vessels if v is not own]
    ordered = [v.trajectory for v in others] + [own.trajectory]
    seeds["scenario_csv"] = _own_dir(root, "scenario_csv") / "ferry.csv"
    write_gemini_csv(seeds["scenario_csv"], ordered, time=time)
    ydir = _own_dir(root, "scenario_yaml")
    write_gemini_csv(ydir / "ferry.csv", ordered, time=time)
    vessels = "".join(
        f"  - {{name: {v.name}, role: {v.role.value}, column: {n}, model: {v.model}}}\n"
        for n, v in enumerate([*others, own], start=1)
    )
    seeds["scenario_yaml"] = ydir / "ferry.yaml"
    seeds["scenario_yaml"].write_text(
        "name: ferry\nseed: 3\norigin: {lat: 63.4336, lon: 10.3926, height: 0.0}\n"
        "environment: {harbour: default, water: flat}\nrig: milliampere\ntrajectory: ferry.csv\nvessels:\n" + vessels
    )

    from families import copy_campaign_seed

    seeds["campaign_yaml"] = copy_campaign_seed(root / "campaign_yaml")

    truth = gt_synth.turning_vessel(duration=20.0)
    t = gt_synth.sample_times(gt_synth.T0, 20.0, 1.0)
    lat, lon, h = gt_synth.antenna_llh(truth, t, 1.0, 0.01, 1, "fuzz")
    seeds["gpx"] = gt_synth.write_gpx(_own_dir(root, "gpx") / "bow.gpx", t, lat, lon, h)
    seeds["nmea"] = gt_synth.write_nmea(_own_dir(root, "nmea") / "bow.nmea", t, lat, lon, h)
    seeds["rtklib"] = gt_synth.write_pos(_own_dir(root, "rtklib") / "bow.pos", t, lat, lon, h)
    seeds["gnss_csv"] = gt_synth.write_csv(_own_dir(root, "gnss_csv") / "bow.csv", t, lat, lon, h)

    rng = np.random.default_rng(5)
    lines = ["scan_time_s,north_m,east_m"]
    for k in range(6):
        for _ in range(3):
            lines.append(f"{2.5 * k:.2f},{rng.uniform(-200, 200):.2f},{rng.uniform(-200, 200):.2f}")
    seeds["radar_csv"] = _own_dir(root, "radar_csv") / "2023-05-10-12-00-00.csv"
    seeds["radar_csv"].write_text("\n".join(lines) + "\n")

    k = 6
    meas = np.empty((k, 1), dtype=object)
    for i in range(k):
        meas[i, 0] = np.vstack([rng.uniform(-300, 300, size=(2 + i % 2, 2)), [[np.inf, np.inf]]])
    seeds["joyride"] = _own_dir(root, "joyride") / "joyride.mat"
    savemat(
        seeds["joyride"],
        {
            "time": 1.6e9 + 2.5 * np.arange(k, dtype=float).reshape(-1, 1),
            "measurements": meas,
            "target": rng.normal(size=(k, 4)),
            "telemetron": rng.normal(size=(k, 4)),
        },
    )
    return seeds


def check_shared_joyride(path: Path) -> None:
    """The real joyride.mat passes :func:`check_mat5` and reads (238 scans)."""
    from seatwin.perception.datasets import JOYRIDE_VARIABLES, check_mat5
    from seatwin.perception.datasets import read_joyride as read

    check_mat5(path, JOYRIDE_VARIABLES)
    assert read(path).time.size == 238
