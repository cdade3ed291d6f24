"""Summaries of a recording for ``seatwin bag info``."""

from __future__ import annotations

import datetime as dt
import os
from pathlib import Path
from typing import Any

from seatwin.recording.chunks import ReadOptions
from seatwin.recording.reader import Recording
from seatwin.recording.sqlite_zstd import bag_compression


def _iso(ns: int | None) -> str | None:
    if ns is None:
        return None
    return dt.datetime.fromtimestamp(ns / 1e9, dt.UTC).isoformat(timespec="milliseconds")


def bag_info(path: str | os.PathLike[str], scan: bool = True, ignore_crc: bool = False) -> dict[str, Any]:
    """Format, time span, completeness and per-topic type/count/rate of a recording.

    ``ignore_crc``: MCAP chunks whose CRC does not match are read, and counted in ``bad_crc``.

    With ``scan`` every message's log time is read (not decoded) to give each topic's own span
    and mean rate (count − 1)/span; without, rate = (count − 1) / bag duration. ``/tf_static`` has no rate.
    """
    with Recording(path, ReadOptions.from_env(ignore_crc=ignore_crc)) as rec:
        spans: dict[str, list[int]] = {}
        counts: dict[str, int] = {}
        if scan:
            for topic, _, ts, _ in rec.raw_messages():  # raw pass, no decoding
                s = spans.setdefault(topic, [ts, ts])
                s[0], s[1] = min(s[0], ts), max(s[1], ts)
                counts[topic] = counts.get(topic, 0) + 1
        duration = rec.duration_s
        topics = {}
        for name, t in sorted(rec.topics.items()):
            n = counts.get(name, t.count) if scan else t.count
            if name == rec.topic_config.tf_static:  # latched: fixed frames, written when known, not at a rate
                rate = None
            elif scan and name in spans and n > 1 and spans[name][1] > spans[name][0]:
                rate = (n - 1) / ((spans[name][1] - spans[name][0]) * 1e-9)
            else:
                rate = (n - 1) / duration if duration > 0 and n > 1 else None
            topics[name] = {"type": t.msgtype, "count": n, "rate_hz": None if rate is None else round(rate, 4)}
        m = rec.manifest or {}
        return {
            "path": str(Path(path)),
            "bag": str(rec.bag),
            "format": rec.format,
            "start_ns": rec.start_ns,
            "end_ns": rec.end_ns,
            "start_utc": _iso(rec.start_ns),
            "end_utc": _iso(rec.end_ns),
            "duration_s": round(duration, 9),
            "message_count": sum(v["count"] for v in topics.values()),
            "complete": rec.complete,
            "recovered": rec.recovered,
            "truncated": rec.truncated,
            "bad_crc": rec.bad_crc,
            "size_bytes": _size(Path(rec.bag)),
            "compression": m.get("compression") or _sqlite_compression(rec),
            "image_format": m.get("image_format"),
            "seatwin_version": m.get("seatwin_version"),
            "seed": m.get("seed"),
            "error": m.get("error"),
            "topics": topics,
        }


def _sqlite_compression(rec: Recording) -> str | None:
    """A foreign rosbag2 SQLite3 folder's compression as ``--compression`` names it (None for other bags)."""
    if rec.format != "sqlite3" or not Path(rec.bag).is_dir():
        return None
    return {"none": "none", "message": "zstd", "file": "zstd-file"}[bag_compression(Path(rec.bag))]


def _size(bag: Path) -> int:
    """Bytes of the bag on disk: its file, or every file of a rosbag2 folder."""
    if bag.is_dir():
        return sum(p.stat().st_size for p in bag.rglob("*") if p.is_file())
    return bag.stat().st_size


def format_info(d: dict[str, Any]) -> str:
    """The :func:`bag_info` summary as aligned text."""
    state = {True: "yes", False: "NO (run did not finish)", None: "unknown (no seatwin manifest)"}[d["complete"]]
    if d["recovered"]:
        state += " — recovered: read up to the last flushed chunk"
    lines = [
        f"path:      {d['path']}",
        f"format:    {d['format']}" + (f"  (bag {d['bag']})" if d["bag"] != d["path"] else ""),
        f"duration:  {d['duration_s']:.3f} s",
        f"start:     {d['start_utc']}  ({(d['start_ns'] or 0) / 1e9:.3f})",
        f"end:       {d['end_utc']}  ({(d['end_ns'] or 0) / 1e9:.3f})",
        f"messages:  {d['message_count']}",
        f"complete:  {state}",
    ]
    if d.get("size_bytes") is not None:
        sqlite = {"zstd": "zstd per message", "zstd-file": "zstd file", "none": "uncompressed"}
        comp = d.get("compression")
        how = [(sqlite.get(comp, comp) if d["format"] == "sqlite3" else f"{comp} chunks")] if comp else []
        how += [f"{d['image_format']} images"] if d.get("image_format") else []
        lines.append(f"size:      {d['size_bytes'] / 1e6:.1f} MB" + (f"  ({', '.join(how)})" if how else ""))
    if d.get("seatwin_version"):
        lines.append(f"seatwin:   {d['seatwin_version']}  seed {d['seed']}")
    if d.get("error"):
        lines.append(f"error:     {d['error']}")
    rows = [
        (k, v["type"], str(v["count"]), "-" if v["rate_hz"] is None else f"{v['rate_hz']:.2f} Hz") for k, v in d["topics"].items()
    ]
    if rows:
        w = [max(len(r[i]) for r in rows + [("topic", "type", "count", "rate")]) for i in range(4)]
        lines.append("topics:")
        lines.append(f"  {'topic':<{w[0]}}  {'type':<{w[1]}}  {'count':>{w[2]}}  {'rate':>{w[3]}}")
        for r in rows:
            lines.append(f"  {r[0]:<{w[0]}}  {r[1]:<{w[1]}}  {r[2]:>{w[2]}}  {r[3]:>{w[3]}}")
    return "\n".join(lines)
