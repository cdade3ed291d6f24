"""Structure-aware mutation families (issue #20): each makes mutants of one kind of attack from a
valid seed file, deterministic in ``random.Random(i)``.

* ``length_forging`` — a u32 that looks like a length/count/size (1 … file size: record and header
  lengths, CDR sequence lengths, PointCloud2 ``point_step``/``width``/``row_step``) becomes 0, ±1,
  ×2, 2³¹, 2³²−1, the file size, …, written as u32 or u64;
* ``bomb`` — one chunk (MCAP, ROS 1) is replaced by a compressed one (zstd/lz4, bz2/lz4): its real
  records recompressed, or zeros inflating to 1 MiB … 1 GiB, declaring the true size or a lie; the
  summary kept (stale) or cut off (an unfinished bag);
* ``sql_types`` — a SQLite3 cell gets another SQL type or an absurd value (BLOB names, REAL
  1.5e300, TEXT timestamps, NULL, ±2⁶³), a row is duplicated, a topic deleted (dangling
  ``topic_id``s);
* ``nan_inf`` — a float32/float64 that holds a plausible value becomes NaN, ±Inf or ±max;
* ``huge_int`` — a timestamp (u64 ns, u32 s) or small count becomes 2³¹, 2³²−1, 2⁶³−1, 2⁶⁴−1, −1;
* MCAP seeds have their CRCs zeroed in half of the mutants (a bag from another writer), else
  nearly all are refused by the data-section CRC before deeper checks run;
* ``yaml`` (scenario and campaign YAML) — alias bombs, 100…10 000-deep nesting, 5 000-digit
  integers, undefined aliases, anchors on random values.
"""

from __future__ import annotations

import bz2
import contextlib
import random
import shutil
import sqlite3
import struct
import tempfile
import zlib
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache, lru_cache
from pathlib import Path

import numpy as np

MIB = 1 << 20
BAG_TARGETS = ("ros1", "mcap", "sqlite3")


# ----------------------------------------------------------------------------- helpers
@lru_cache(maxsize=8)
def _u32_candidates(data: bytes, lo: int, hi: int) -> np.ndarray:
    """Offsets whose little-endian u32 lies in [lo, hi]."""
    a = np.frombuffer(data, np.uint8)
    if a.size < 4:
        return np.zeros(0, np.int64)
    b = [a[k : a.size - 3 + k].astype(np.uint32) for k in range(4)]
    v = b[0] | b[1] << 8 | b[2] << 16 | b[3] << 24
    return np.flatnonzero((v >= lo) & (v <= hi))


@lru_cache(maxsize=8)
def _u64_candidates(data: bytes, lo: int, hi: int) -> np.ndarray:
    out = []
    for k in range(8):
        n = (len(data) - k) // 8
        v = np.frombuffer(data, "<u8", count=n, offset=k) if n > 0 else np.zeros(0, np.uint64)
        out.append(np.flatnonzero((v >= lo) & (v <= hi)) * 8 + k)
    return np.sort(np.concatenate(out)) if out else np.zeros(0, np.int64)


@lru_cache(maxsize=8)
def _float_candidates(data: bytes, width: int) -> np.ndarray:
    out = []
    for k in range(width):
        n = (len(data) - k) // width
        if n <= 0:
            continue
        with np.errstate(all="ignore"):
            v = np.abs(np.frombuffer(data, "<f4" if width == 4 else "<f8", count=n, offset=k).astype(np.float64))
            out.append(np.flatnonzero((v > 1e-3) & (v < 1e7)) * width + k)
    return np.sort(np.concatenate(out)) if out else np.zeros(0, np.int64)


def _put(data: bytes, pos: int, raw: bytes) -> bytes:
    return data[:pos] + raw + data[pos + len(raw) :]


def _pick(rng: random.Random, cands: np.ndarray) -> int | None:
    return int(cands[rng.randrange(cands.size)]) if cands.size else None


# ----------------------------------------------------------------------------- families over bytes
def length_forging(rng: random.Random, data: bytes) -> bytes:
    for _ in range(rng.randint(1, 2)):
        pos = _pick(rng, _u32_candidates(data, 1, max(len(data), 1)))
        if pos is None:
            return data
        (old,) = struct.unpack_from("<I", data, pos)
        new = rng.choice([0, old - 1, old + 1, 2 * old, old + 4096, len(data), 2**31 - 1, 2**31, 2**32 - 1, rng.randrange(2**32)])
        if rng.random() < 0.3 and pos + 8 <= len(data):
            data = _put(data, pos, struct.pack("<Q", rng.choice([new, 2**63 - 1, 2**63, 2**64 - 1, 2**40])))
        else:
            data = _put(data, pos, struct.pack("<I", new % 2**32))
    return data


def nan_inf(rng: random.Random, data: bytes) -> bytes:
    for _ in range(rng.randint(1, 3)):
        width = rng.choice([4, 8])
        pos = _pick(rng, _float_candidates(data, width))
        if pos is None:
            continue
        value = rng.choice([float("nan"), float("inf"), float("-inf"), -0.0, 3.4e38 if width == 4 else 1.7e308, -1e30])
        data = _put(data, pos, struct.pack("<f" if width == 4 else "<d", value))
    return data


def huge_int(rng: random.Random, data: bytes) -> bytes:
    kind = rng.choice(["ns", "sec", "count"])
    if kind == "ns":  # log times and stamps in ns (2001 … 2033)
        pos = _pick(rng, _u64_candidates(data, 10**18, 2 * 10**18))
        raw = struct.pack("<Q", rng.choice([2**63 - 1, 2**63, 2**64 - 1, 0, 1]))
    elif kind == "sec":
        pos = _pick(rng, _u32_candidates(data, 10**9, 2 * 10**9))
        raw = struct.pack("<I", rng.choice([2**31 - 1, 2**31, 2**32 - 1, 0]))
    else:
        pos = _pick(rng, _u32_candidates(data, 1, 4096))
        raw = struct.pack("<I", rng.choice([2**31 - 1, 2**31, 2**32 - 1, 2**30]))
    return data if pos is None else _put(data, pos, raw)


# ----------------------------------------------------------------------------- bombs
@cache
def _zeros_packed(kind: str, size: int) -> bytes:
    """``size`` zero bytes compressed with ``kind`` (made once: the bombs)."""
    zeros = bytes(MIB)
    n = size // MIB
    if kind == "zstd":
        from backports import zstd

        c = zstd.ZstdCompressor()
        return b"".join(c.compress(zeros) for _ in range(n)) + c.flush()
    if kind == "lz4":
        from lz4.frame import LZ4FrameCompressor

        c = LZ4FrameCompressor()
        return c.begin() + b"".join(c.compress(zeros) for _ in range(n)) + c.flush()
    c = bz2.BZ2Compressor(1)
    return b"".join(c.compress(zeros) for _ in range(n)) + c.flush()


def _pack(kind: str, data: bytes) -> bytes:
    if kind == "zstd":
        from backports import zstd

        return zstd.compress(data)
    if kind == "lz4":
        from lz4.frame import compress

        return compress(data)
    return bz2.compress(data)


def _payload(rng: random.Random, kind: str, records: bytes) -> tuple[bytes, int]:
    """(compressed bytes, their true uncompressed size): the chunk's records or zeros (a bomb)."""
    if rng.random() < 0.3:
        return _pack(kind, records), len(records)
    size = rng.choice([1, 64, 300, 1024]) * MIB
    return _zeros_packed(kind, size), size


def _declared(rng: random.Random, true: int) -> int:
    return rng.choice([true, true, max(true // 2, 1), 10, true + 1, 2 * true, 2**30, 2**32 - 1, 2**40])


def _mcap_chunks(data: bytes) -> list[tuple[int, int]]:
    out, pos = [], 8
    while pos + 9 <= len(data):
        op, length = struct.unpack_from("<BQ", data, pos)
        if op == 0x06:
            out.append((pos, length))
        if op in (0x02, 0x0F) or pos + 9 + length > len(data):
            break
        pos += 9 + length
    return out


def bomb_mcap(rng: random.Random, data: bytes) -> bytes:
    chunks = _mcap_chunks(data)
    if not chunks:
        return data
    at, length = rng.choice(chunks)
    body = data[at + 9 : at + 9 + length]
    start, end, usize, _crc, clen = struct.unpack_from("<QQQII", body)
    rlen_at = 32 + clen
    (rlen,) = struct.unpack_from("<Q", body, rlen_at)
    records = body[rlen_at + 8 : rlen_at + 8 + rlen]
    kind = rng.choice(["zstd", "lz4"])
    packed, true = _payload(rng, kind, records)
    declared = _declared(rng, true)
    crc = 0 if true != len(records) or rng.random() < 0.5 else zlib.crc32(records)
    head = struct.pack("<QQQII", start, end, declared, crc, len(kind)) + kind.encode() + struct.pack("<Q", len(packed))
    chunk = struct.pack("<BQ", 0x06, len(head) + len(packed)) + head + packed
    rest = data[at + 9 + length :]
    if rng.random() < 0.5:  # an unfinished bag: no summary, no footer
        cut = rest.find(b"\x0f\x04\x00\x00\x00\x00\x00\x00\x00")
        rest = rest[:cut] if cut >= 0 else rest
    return data[:at] + chunk + rest


def bomb_ros1(rng: random.Random, data: bytes) -> bytes:
    from seatwin.recording.ros1_check import MAGIC, records

    pos, chunks = len(MAGIC), []
    for hdr, body, end in records(data, pos):
        if hdr.get("op", b"")[:1] == b"\x05":
            chunks.append((pos, end, hdr, bytes(body)))
        pos = end
    if not chunks:
        return data
    at, end, hdr, body = rng.choice(chunks)
    comp = hdr.get("compression", b"none").decode()
    if comp == "bz2":
        body = bz2.decompress(body)
    elif comp == "lz4":
        from lz4.frame import decompress

        body = decompress(body)
    kind = rng.choice(["bz2", "lz4"])
    packed, true = _payload(rng, kind, body)
    fields = {"op": b"\x05", "compression": kind.encode(), "size": struct.pack("<I", _declared(rng, true) % 2**32)}
    raw = b"".join(struct.pack("<I", len(k) + 1 + len(v)) + k.encode() + b"=" + v for k, v in fields.items())
    chunk = struct.pack("<I", len(raw)) + raw + struct.pack("<I", len(packed)) + packed
    return data[:at] + chunk + data[end:]


# ----------------------------------------------------------------------------- SQLite3
_SQL_VALUES: list[object] = [
    b"abc",
    b"",
    1.5e300,
    -1.5e300,
    0.5,
    "text",
    "",
    None,
    -1,
    -(2**63),
    2**63 - 1,
    0,
    "\udcff".encode("utf-8", "surrogatepass"),
]


def sql_types(rng: random.Random, data: bytes) -> bytes:
    with tempfile.TemporaryDirectory() as tmp:
        db = Path(tmp) / "m.db3"
        db.write_bytes(data)
        con = sqlite3.connect(db)
        try:
            tables = [r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE type = 'table'")]
            for _ in range(rng.randint(1, 2)):
                op = rng.random()
                table = rng.choice(["topics", "messages", "messages", *tables])
                ids = [r[0] for r in con.execute(f"SELECT rowid FROM {table}")]
                if not ids:
                    continue
                row = rng.choice(ids)
                if op < 0.65:
                    cols = [r[1] for r in con.execute(f"PRAGMA table_info({table})")]
                    col = rng.choice(cols)
                    value = rng.choice(_SQL_VALUES)
                    with contextlib.suppress(sqlite3.IntegrityError):  # e.g. a second row with the same primary key
                        con.execute(f"UPDATE {table} SET {col} = ? WHERE rowid = ?", (value, row))
                elif op < 0.8:
                    cols = [r[1] for r in con.execute(f"PRAGMA table_info({table})") if r[5] == 0]  # not the primary key
                    names = ", ".join(cols)
                    con.execute(f"INSERT INTO {table} ({names}) SELECT {names} FROM {table} WHERE rowid = ?", (row,))
                elif op < 0.9:
                    topics = [r[0] for r in con.execute("SELECT rowid FROM topics")]
                    con.execute("DELETE FROM topics WHERE rowid = ?", (rng.choice(topics),))
                else:
                    con.execute("UPDATE messages SET topic_id = ? WHERE rowid = ?", (rng.choice([0, 99, -1, 2**62]), row))
            con.commit()
        finally:
            con.close()
        return db.read_bytes()


# ----------------------------------------------------------------------------- YAML
def _alias_bomb(levels: int, width: int) -> str:
    lines = [f"l0: &l0 [{', '.join(['lol'] * width)}]"]
    for k in range(1, levels):
        lines.append(f"l{k}: &l{k} [{', '.join([f'*l{k - 1}'] * width)}]")
    return "\n".join(lines)


def yaml_family(rng: random.Random, data: bytes) -> bytes:
    text = data.decode("utf-8", "replace")
    lines = text.split("\n")
    keyed = [i for i, ln in enumerate(lines) if ":" in ln and not ln.lstrip().startswith("#") and not ln.startswith(" ")]
    kind = rng.choice(["bomb_key", "bomb_value", "depth_list", "depth_map", "digits", "undefined_alias", "anchor"])
    i = rng.choice(keyed) if keyed else 0
    key = lines[i].split(":", 1)[0] if keyed else "x"
    if kind == "bomb_key":
        return (_alias_bomb(rng.choice([6, 9, 12]), rng.choice([9, 10])) + "\n" + text).encode()
    if kind == "bomb_value":
        bomb = _alias_bomb(rng.choice([6, 9]), 9)
        last = bomb.rsplit("\n", 1)[-1].split(":", 1)[0]
        lines[i] = f"{key}: *{last}"
        return (bomb + "\n" + "\n".join(lines)).encode()
    if kind == "depth_list":
        d = rng.choice([100, 1000, 10000])
        lines[i] = f"{key}: " + "[" * d + "1" + "]" * d
    elif kind == "depth_map":
        d = rng.choice([100, 1000, 5000])
        lines[i] = f"{key}: " + "{a: " * d + "1" + "}" * d
    elif kind == "digits":
        lines[i] = f"{key}: {rng.choice(['', '-'])}{'9' * rng.choice([400, 4300, 5000, 20000])}"
    elif kind == "undefined_alias":
        lines[i] = f"{key}: *nowhere"
    else:
        j = rng.choice(keyed) if keyed else 0
        lines[i] = lines[i].replace(":", ": &x", 1) if not lines[i].rstrip().endswith(":") else lines[i]
        lines[j] = f"{lines[j].split(':', 1)[0]}: *x"
    return "\n".join(lines).encode()


# ----------------------------------------------------------------------------- the families
@dataclass(frozen=True)
class Family:
    name: str
    targets: tuple[str, ...]
    mutate: Callable[[random.Random, bytes, str], bytes]


def _by_target(**makers: Callable[[random.Random, bytes], bytes]) -> Callable[[random.Random, bytes, str], bytes]:
    return lambda rng, data, target: makers[target](rng, data)


def without_crcs(data: bytes) -> bytes:
    """An MCAP file with its chunk and data-section CRCs set to 0 ("not written", as rosbags writes):
    without them nearly every mutant of our bags is refused by a CRC, and the deeper checks go untried."""
    out = bytearray(data)
    pos = 8
    while pos + 9 <= len(out):
        op, length = struct.unpack_from("<BQ", out, pos)
        if op == 0x06 and pos + 9 + 28 <= len(out):
            struct.pack_into("<I", out, pos + 9 + 24, 0)
        elif op == 0x0F and pos + 13 <= len(out):
            struct.pack_into("<I", out, pos + 9, 0)
        if op in (0x02, 0x0F) or pos + 9 + length > len(out):
            break
        pos += 9 + length
    return bytes(out)


def _foreign_mcap(mutate: Callable[[random.Random, bytes, str], bytes]) -> Callable[[random.Random, bytes, str], bytes]:
    """``mutate``, applied to an MCAP seed without CRCs half of the time."""

    def run(rng: random.Random, data: bytes, target: str) -> bytes:
        if target == "mcap" and rng.random() < 0.5:
            data = without_crcs(data)
        return mutate(rng, data, target)

    return run


FAMILIES: dict[str, Family] = {
    f.name: f
    for f in (
        Family("length_forging", ("ros1", "mcap"), _foreign_mcap(lambda rng, data, _t: length_forging(rng, data))),
        Family("bomb", ("ros1", "mcap"), _foreign_mcap(_by_target(ros1=bomb_ros1, mcap=bomb_mcap))),
        Family("sql_types", ("sqlite3",), lambda rng, data, _t: sql_types(rng, data)),
        Family("nan_inf", BAG_TARGETS, _foreign_mcap(lambda rng, data, _t: nan_inf(rng, data))),
        Family("huge_int", BAG_TARGETS, _foreign_mcap(lambda rng, data, _t: huge_int(rng, data))),
        Family("yaml", ("scenario_yaml", "campaign_yaml"), lambda rng, data, _t: yaml_family(rng, data)),
    )
}


def family_mutant(family: str, target: str, i: int, data: bytes) -> bytes:
    """Mutant ``i`` of ``family`` for ``target`` (deterministic)."""
    return FAMILIES[family].mutate(random.Random(f"{family}/{target}/{i}"), data, target)


def copy_campaign_seed(dest: Path) -> Path:
    """The example campaign YAML as a seed (in a folder of its own)."""
    src = Path(__file__).resolve().parents[2] / "docs" / "examples" / "campaign.yaml"
    dest.mkdir(parents=True, exist_ok=True)
    return Path(shutil.copy(src, dest / "campaign.yaml"))
