"""Screenshot a seatwin run in a Foxglove-compatible web viewer, in a real headless browser.

The viewer is Lichtblick (the open-source, MPL-2.0 fork of Foxglove Studio), built from source outside this
repository (its web build, ``yarn web:build:prod``: see docs/validation.md, "Foxglove view"); this script
never ships it. It

1. serves the built web app, the run's MCAP and a Foxglove layout from one local HTTP server (with the
   ``Range`` requests and ``Accept-Ranges`` header Lichtblick's remote-file reader needs);
2. opens ``/?ds=remote-file&ds.url=…/run.mcap&layoutUrl=…/layout.json&time=…`` in headless Chromium, driven
   over the Chrome DevTools Protocol (``websockets``, a test dependency: no browser-automation package);
3. waits until the layout's panels are up and the player is ready, reads the viewer's Topics and Alerts lists,
   closes its left sidebar, waits until every panel has drawn and the page holds still, and saves a PNG of the
   page, with a report of what it showed (panels, their places, topics with message counts, alerts).

    SEATWIN_VIEWER_DIST=/work/lichtblick/web/.webpack \\
        python tools/foxglove_screenshot.py runs/ferry_fox.tracked --at 8 --out docs/foxglove/lichtblick-view.png

``--live`` instead serves the run as ``seatwin view RUN`` does (the Foxglove SDK's WebSocket server, looped at real
time) and opens ``/?ds=foxglove-websocket&ds.url=ws://127.0.0.1:PORT&layoutUrl=…``.
``tests/report/test_foxglove_viewer.py`` runs the same steps and checks the page.
"""

from __future__ import annotations

import argparse
import base64
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request
from collections.abc import Callable, Iterator
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, field
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any
from urllib.parse import quote, urlsplit

ROOT = Path(__file__).resolve().parents[1]
LAYOUT = ROOT / "docs" / "foxglove" / "seatwin-layout.json"
BROWSERS = ("chromium", "chromium-browser", "google-chrome")


def find_browser() -> str | None:
    """The first Chromium-family browser on PATH."""
    return next((shutil.which(b) for b in BROWSERS if shutil.which(b)), None)


def run_mcap(run: Path) -> Path:
    """The MCAP of a run directory (``RUN/recording/*.mcap``), or ``run`` itself when it is an ``.mcap``."""
    if run.is_file() and run.suffix == ".mcap":
        return run
    found = sorted(run.glob("recording/*.mcap")) or sorted(run.glob("*.mcap"))
    if not found:
        raise FileNotFoundError(f"{run}: no MCAP (record the run with --format mcap, the default)")
    return found[0]


# ---------------------------------------------------------------------------------------------- HTTP server


class _Handler(SimpleHTTPRequestHandler):
    """Static files from the viewer's build, named extra files under ``/seatwin/``, single byte ranges."""

    extra: dict[str, Path] = {}

    def log_message(self, format: str, *args: Any) -> None:  # noqa: A002 (the base class's name)
        pass

    def end_headers(self) -> None:
        self.send_header("Accept-Ranges", "bytes")
        self.send_header("Access-Control-Allow-Origin", "*")
        self.send_header("Access-Control-Expose-Headers", "Accept-Ranges, Content-Range, Content-Length")
        self.send_header("Cross-Origin-Opener-Policy", "same-origin")
        self.send_header("Cross-Origin-Embedder-Policy", "credentialless")
        self.send_header("Cache-Control", "no-store")
        super().end_headers()

    def translate_path(self, path: str) -> str:
        name = urlsplit(path).path
        if name in self.extra:
            return str(self.extra[name])
        return super().translate_path(path)

    def send_head(self) -> Any:
        rng = self.headers.get("Range")
        path = Path(self.translate_path(self.path))
        if rng is None or not path.is_file():
            return super().send_head()
        m = re.fullmatch(r"bytes=(\d*)-(\d*)", rng.strip())
        size = path.stat().st_size
        if m is None or (m[1] == "" and m[2] == ""):
            self.send_error(416)
            return None
        if m[1] == "":  # suffix range: the last N bytes
            start, end = max(size - int(m[2]), 0), size - 1
        else:
            start, end = int(m[1]), min(int(m[2]) if m[2] else size - 1, size - 1)
        if start >= size or end < start:
            self.send_response(416)
            self.send_header("Content-Range", f"bytes */{size}")
            self.end_headers()
            return None
        with path.open("rb") as f:
            f.seek(start)
            body = f.read(end - start + 1)
        self.send_response(206)
        self.send_header("Content-Type", self.guess_type(str(path)))
        self.send_header("Content-Range", f"bytes {start}-{end}/{size}")
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        return io.BytesIO(body)  # copied to the socket by do_GET, skipped by do_HEAD


class _Server(ThreadingHTTPServer):
    daemon_threads = True

    def handle_error(self, request: Any, client_address: Any) -> None:
        """The browser cancels range reads it no longer needs: a reset connection is no error."""
        exc = sys.exc_info()[1]
        if not isinstance(exc, ConnectionError):
            super().handle_error(request, client_address)


@contextmanager
def serve(root: Path, extra: dict[str, Path]) -> Iterator[str]:
    """Serve ``root`` and ``extra`` (URL path → file) on a free localhost port; yields the base URL."""
    handler = type("Handler", (_Handler,), {"extra": dict(extra)})

    def make(*args: Any) -> _Handler:
        return handler(*args, directory=str(root))

    server = _Server(("127.0.0.1", 0), make)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()
        thread.join(timeout=5)


# --------------------------------------------------------------------------------------- the browser (CDP)


class Browser:
    """Headless Chromium with one page, driven over the Chrome DevTools Protocol."""

    def __init__(self, executable: str, width: int, height: int, timeout_s: float = 30.0) -> None:
        from websockets.sync.client import connect

        self.width, self.height = width, height
        self._profile = tempfile.mkdtemp(prefix="seatwin-chromium-")
        args = [
            executable, "--headless=new", "--no-sandbox", "--no-first-run", "--no-default-browser-check",
            "--hide-scrollbars", "--mute-audio", "--remote-debugging-port=0", f"--user-data-dir={self._profile}",
            f"--window-size={width},{height}", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
            "--ignore-gpu-blocklist", "about:blank",
        ]  # fmt: skip
        self._proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        port_file = Path(self._profile) / "DevToolsActivePort"
        deadline = time.monotonic() + timeout_s
        while not (port_file.exists() and len(port_file.read_text().splitlines()) >= 2):
            if self._proc.poll() is not None or time.monotonic() > deadline:
                self.close()
                raise RuntimeError(f"{executable} did not open its DevTools port")
            time.sleep(0.1)
        port = int(port_file.read_text().splitlines()[0])
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=timeout_s) as r:
            pages = [t for t in json.load(r) if t["type"] == "page"]
        self._stack = ExitStack()
        self._ws = self._stack.enter_context(connect(pages[0]["webSocketDebuggerUrl"], max_size=None, open_timeout=timeout_s))
        self._id = 0
        self.console: list[str] = []
        """Console errors and uncaught exceptions, in order."""
        self.call("Page.enable")
        self.call("Runtime.enable")
        self.call("Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=1, mobile=False)

    def _event(self, msg: dict[str, Any]) -> None:
        method, p = msg.get("method"), msg.get("params", {})
        if method == "Runtime.consoleAPICalled" and p.get("type") == "error":
            self.console.append(" ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", [])))
        elif method == "Runtime.exceptionThrown":
            d = p.get("exceptionDetails", {})
            self.console.append(str(d.get("exception", {}).get("description", d.get("text", ""))))

    def call(self, method: str, timeout_s: float = 60.0, **params: Any) -> dict[str, Any]:
        """Send a CDP command and wait for its result (events that arrive meanwhile are recorded)."""
        self._id += 1
        self._ws.send(json.dumps({"id": self._id, "method": method, "params": params}))
        deadline = time.monotonic() + timeout_s
        while True:
            msg = json.loads(self._ws.recv(timeout=max(deadline - time.monotonic(), 0.01)))
            if msg.get("id") == self._id:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg.get("result", {})
            self._event(msg)

    def evaluate(self, expression: str) -> Any:
        """The JSON value of a JavaScript expression in the page (promises awaited)."""
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            raise RuntimeError(f"page script failed: {r['exceptionDetails'].get('text')}")
        return r["result"].get("value")

    def navigate(self, url: str) -> None:
        self.call("Page.navigate", url=url)

    def screenshot(self) -> bytes:
        """A PNG of the viewport."""
        r = self.call("Page.captureScreenshot", format="png", captureBeyondViewport=False)
        return base64.b64decode(r["data"])

    def close(self) -> None:
        stack = getattr(self, "_stack", None)
        if stack is not None:
            stack.close()
        if self._proc.poll() is None:
            self._proc.terminate()
            try:
                self._proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self._proc.kill()
                self._proc.wait()
        shutil.rmtree(self._profile, ignore_errors=True)


# ------------------------------------------------------------------------------------------- the page state

PAGE_STATE_JS = r"""
(() => {
  const rect = (el) => { const r = el.getBoundingClientRect(); return [r.left, r.top, r.width, r.height]; };
  const panels = [...document.querySelectorAll(".mosaic-window")].map((el) => {
    const logs = [...el.querySelectorAll("button")].map((b) => b.getAttribute("title") || "")
      .find((t) => t.startsWith("Show logs"));
    return {
      rect: rect(el),
      title: (el.querySelector("[data-testid=mosaic-drag-handle]") || el).innerText.trim().split("\n")[0],
      canvases: el.querySelectorAll("canvas").length,
      canvas: el.querySelector("canvas") ? rect(el.querySelector("canvas")) : null,
      logs: logs === undefined ? 0 : Number((logs.match(/\d+/) || ["0"])[0]),
    };
  });
  const button = (name) => [...document.querySelectorAll("button")].find(
    (b) => b.getAttribute("aria-label") === name || b.getAttribute("title") === name);
  const play = button("Play");
  return {
    title: document.title,
    panels,
    playReady: play !== undefined && !play.disabled,
    source: (document.querySelector("header, .MuiAppBar-root") || document.body || { innerText: "" }).innerText.slice(0, 500),
  };
})()
"""

SIDEBAR_TAB_JS = r"""
(async (id) => {
  const tab = document.querySelector(`[data-testid=${id}]`);
  if (!tab) return null;
  tab.click();
  await new Promise((r) => setTimeout(r, 1000));
  return document.body.innerText;
})
"""

ALERTS_JS = r"""
[...document.querySelectorAll(".MuiAccordionSummary-root")].map((el) => ({
  message: el.getAttribute("title") || el.innerText,
  fill: (el.querySelector("svg[fill]") || { getAttribute: () => "" }).getAttribute("fill").toLowerCase(),
}))
"""


def listed_topics(text: str) -> dict[str, tuple[str, int | None]]:
    """Topic → (schema, message count) from the page's text with the Topics list open: each topic a line, then its
    schema, its rate ("—" while unknown) and its count ("—", here None: advertised, nothing received)."""
    lines = [ln.strip() for ln in text.splitlines()]
    out: dict[str, tuple[str, int | None]] = {}
    for i, line in enumerate(lines[:-1]):
        if line.startswith("/") and re.fullmatch(r"\w+/msg/\w+", lines[i + 1]):
            has_count = i + 3 < len(lines) and (lines[i + 2].endswith("Hz") or lines[i + 2] == "—") and lines[i + 3].isdigit()
            out[line] = (lines[i + 1], int(lines[i + 3]) if has_count else None)
    return out


SEVERITY = {"#db3553": "error", "#f54966": "error", "#eba800": "warn", "#1ea7fd": "info", "#29bee7": "info"}
"""Lichtblick's alert icons by their fill (theme palette error/warning/info, light and dark)."""


@dataclass
class ViewerShot:
    """What the viewer showed: the PNG, the page's state when it was taken, the page's text with the viewer's Topics
    list open (what it read from the data source: :func:`listed_topics`), its alerts (severity, message) and the
    console's errors."""

    png: bytes
    url: str
    state: dict[str, Any]
    topics_text: str = ""
    alerts: list[tuple[str, str]] = field(default_factory=list)
    console: list[str] = field(default_factory=list)
    waited_s: float = 0.0


def viewer_url(base: str, at: str | None = None, websocket: str | None = None) -> str:
    """The deep link that opens the served MCAP (at POSIX time ``at``, if given) — or, with ``websocket``, that
    Foxglove WebSocket server — with the served layout."""
    if websocket is None:
        url = f"{base}/?ds=remote-file&ds.url={quote(base + '/seatwin/run.mcap', safe='')}"
    else:
        url = f"{base}/?ds=foxglove-websocket&ds.url={quote(websocket, safe='')}"
    url += f"&layoutUrl={quote(base + '/seatwin/seatwin-layout.json', safe='')}"
    if at is not None:
        url += f"&time={quote(at, safe='')}"
    return url


def mcap_start_ns(mcap: Path) -> int:
    """The first message's log time of an MCAP [ns]."""
    from mcap.reader import make_reader

    with mcap.open("rb") as f:
        summary = make_reader(f).get_summary()
    if summary is None or summary.statistics is None:
        raise ValueError(f"{mcap}: no summary statistics (repair the bag with `seatwin bag repair`)")
    return summary.statistics.message_start_time


def _drawn(png: bytes, panels: list[dict[str, Any]]) -> tuple[bool, Any]:
    """Whether every panel below its toolbar shows something (not one flat colour), and the pixels."""
    import numpy as np
    from PIL import Image

    px = np.asarray(Image.open(io.BytesIO(png)).convert("L"), dtype=np.float32)
    ok = True
    for p in panels:
        x, y, w, h = (round(v) for v in p["rect"])
        ok &= bool(px[y + 30 : y + h, x : x + w].std() > 10.0)
    return ok, px


def _prepared(dist: Path, browser: str | None, layout: Path) -> tuple[str, int]:
    """The browser to drive (``browser`` or the first Chromium on PATH), once ``dist`` is known to hold a web build,
    and the number of panels ``layout`` opens."""
    executable = browser or find_browser()
    if executable is None:
        raise FileNotFoundError("no Chromium-family browser on PATH")
    if not (dist / "index.html").is_file():
        raise FileNotFoundError(f"{dist}: no index.html (the viewer's web build)")
    return executable, len(_leaves(json.loads(layout.read_text())["layout"]))


def screenshot_run(
    dist: Path,
    run: Path,
    *,
    layout: Path = LAYOUT,
    at_s: float | None = None,
    width: int = 1400,
    height: int = 850,
    close_sidebar: bool = True,
    timeout_s: float = 180.0,
    browser: str | None = None,
) -> ViewerShot:
    """Open ``run`` (a run directory or an ``.mcap``) with ``layout`` in the viewer built at ``dist``, ``at_s``
    seconds after its first message, and screenshot it once the panels are up, the player is ready, every panel
    has drawn and two screenshots a second apart agree. Before that, the viewer's Topics and Alerts lists are read
    (then its left sidebar closed, unless ``close_sidebar`` is False)."""
    executable, n_panels = _prepared(dist, browser, layout)
    mcap = run_mcap(run)
    at = None
    if at_s is not None:
        ns = mcap_start_ns(mcap) + round(at_s * 1e9)
        at = f"{ns // 1_000_000_000}.{ns % 1_000_000_000:09d}"
    extra = {"/seatwin/run.mcap": mcap, "/seatwin/seatwin-layout.json": layout}
    with serve(dist, extra) as base:
        url = viewer_url(base, at)
        return _shoot(executable, url, n_panels, width, height, live=False, close_sidebar=close_sidebar, timeout_s=timeout_s)


def screenshot_live(
    dist: Path,
    run: Path,
    *,
    layout: Path = LAYOUT,
    width: int = 1400,
    height: int = 850,
    close_sidebar: bool = True,
    timeout_s: float = 180.0,
    browser: str | None = None,
) -> ViewerShot:
    """``run`` served as ``seatwin view RUN`` serves it (:class:`~seatwin.recording.view.RecordingViewer`, the
    Foxglove SDK's WebSocket server, played in a loop at real time) and watched in the viewer built at ``dist``
    through its Foxglove WebSocket connection with ``layout``; screenshot once the panels are up and have drawn
    (the page is live: no stillness is waited for)."""
    from seatwin.recording.view import RecordingViewer

    executable, n_panels = _prepared(dist, browser, layout)
    stop = threading.Event()
    with RecordingViewer(run, port=0) as viewer, serve(dist, {"/seatwin/seatwin-layout.json": layout}) as base:
        port = viewer.start()
        player = threading.Thread(target=viewer.play_loop, args=(1.0, stop), daemon=True)
        player.start()

        def stop_serving() -> None:  # before the browser goes: the server would log every message it cannot send
            stop.set()
            player.join(timeout=10)
            viewer.close()

        try:
            url = viewer_url(base, websocket=f"ws://127.0.0.1:{port}")
            return _shoot(
                executable, url, n_panels, width, height, live=True, close_sidebar=close_sidebar, timeout_s=timeout_s,
                before_close=stop_serving,
            )  # fmt: skip
        finally:
            stop_serving()


def _shoot(
    executable: str,
    url: str,
    n_panels: int,
    width: int,
    height: int,
    *,
    live: bool,
    close_sidebar: bool,
    timeout_s: float,
    before_close: Callable[[], None] | None = None,
) -> ViewerShot:
    """Open ``url``, wait for ``n_panels`` panels (and a ready player unless ``live``), read the Topics and Alerts
    lists, close the sidebar, wait until every panel has drawn (and, unless ``live``, two screenshots a second
    apart agree) and screenshot."""
    import numpy as np

    page = Browser(executable, width, height)
    try:
        t0 = time.monotonic()
        page.navigate(url)
        state: dict[str, Any] = {}
        while not (len(state.get("panels", [])) >= n_panels and (live or state.get("playReady"))):
            if time.monotonic() - t0 > timeout_s:
                raise TimeoutError(f"viewer not ready after {timeout_s:.0f} s: {json.dumps(state)[:2000]}")
            time.sleep(0.5)
            state = page.evaluate(PAGE_STATE_JS) or {}
        previous = None
        if live:  # the topics arrive with the connection: wait until every panel has drawn
            while not _drawn(page.screenshot(), state["panels"])[0]:
                if time.monotonic() - t0 > timeout_s:
                    raise TimeoutError(f"the panels did not draw in {timeout_s:.0f} s")
                time.sleep(1.0)
                state = page.evaluate(PAGE_STATE_JS) or {}
        # The Topics list is virtualised (only the rows in view exist): read it in a page tall enough for all.
        page.call("Emulation.setDeviceMetricsOverride", width=width, height=4000, deviceScaleFactor=1, mobile=False)
        topics, listed, seen = "", {}, None
        while not listed or set(listed) != seen:  # the list fills as the source is read: until it holds still
            if time.monotonic() - t0 > timeout_s:
                raise TimeoutError(f"the Topics list did not fill in {timeout_s:.0f} s")
            seen = set(listed)
            topics = page.evaluate(f"{SIDEBAR_TAB_JS}('topics-left')") or ""
            listed = listed_topics(topics)
        page.call("Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=1, mobile=False)
        page.evaluate(f"{SIDEBAR_TAB_JS}('alerts-left')")
        alerts = [(SEVERITY.get(a["fill"], a["fill"] or "?"), a["message"]) for a in page.evaluate(ALERTS_JS) or []]
        if close_sidebar:
            page.evaluate("document.querySelector('[data-testid=sidebar-close-left]')?.click()")
        while True:  # every panel drawn, and (a recording) the page still
            time.sleep(1.0)
            state = page.evaluate(PAGE_STATE_JS) or {}
            png = page.screenshot()
            drawn, px = _drawn(png, state["panels"])
            if drawn and (live or (previous is not None and float(np.mean(np.abs(px - previous) > 8)) < 0.002)):
                break
            if time.monotonic() - t0 > timeout_s:
                raise TimeoutError(f"the panels did not settle in {timeout_s:.0f} s (drawn: {drawn})")
            previous = px
        return ViewerShot(png, url, state, topics, alerts, list(page.console), time.monotonic() - t0)
    finally:
        if before_close is not None:
            before_close()
        page.close()


def _leaves(node: Any) -> list[str]:
    if isinstance(node, str):
        return [node]
    return _leaves(node["first"]) + _leaves(node["second"])


def save_png(png: bytes, out: Path, max_bytes: int = 400_000) -> Path:
    """Write ``png`` optimised (Pillow), as a palette image when the full-colour one exceeds ``max_bytes``."""
    from PIL import Image

    img = Image.open(io.BytesIO(png)).convert("RGB")
    buf = io.BytesIO()
    img.save(buf, format="PNG", optimize=True)
    if buf.tell() > max_bytes:
        buf = io.BytesIO()
        img.quantize(colors=256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE).save(buf, format="PNG", optimize=True)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(buf.getvalue())
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run", type=Path, help="a run directory (RUN/recording/*.mcap) or an .mcap")
    ap.add_argument("--out", type=Path, required=True, help="the PNG to write")
    ap.add_argument("--dist", type=Path, default=os.environ.get("SEATWIN_VIEWER_DIST"), help="the viewer's web build")
    ap.add_argument("--layout", type=Path, default=LAYOUT)
    ap.add_argument("--at", type=float, default=None, help="seconds after the run's first message")
    ap.add_argument("--size", default="1400x850", help="viewport WIDTHxHEIGHT")
    ap.add_argument("--live", action="store_true", help="serve the run as `seatwin view` does (Foxglove WebSocket), not by URL")
    args = ap.parse_args()
    if args.dist is None:
        ap.error("--dist or SEATWIN_VIEWER_DIST: the built web viewer (its folder with index.html)")
    w, h = (int(v) for v in args.size.lower().split("x"))
    if args.live:
        shot = screenshot_live(args.dist, args.run, layout=args.layout, width=w, height=h)
    else:
        shot = screenshot_run(args.dist, args.run, layout=args.layout, at_s=args.at, width=w, height=h)
    save_png(shot.png, args.out)
    print(f"{args.out}: {args.out.stat().st_size / 1e3:.0f} kB, {w}×{h}, ready after {shot.waited_s:.1f} s; {shot.url}")
    for p in shot.state.get("panels", []):
        print(f"  panel {p['title']!r} at {[round(v) for v in p['rect']]}: {p['canvases']} canvas(es), {p['logs']} log line(s)")
    listed = listed_topics(shot.topics_text)
    print(f"  {len(listed)} topics listed:", ", ".join(f"{t} ({n})" for t, (_, n) in listed.items()))
    for severity, message in shot.alerts:
        print(f"  alert ({severity}): {message}")
    for c in shot.console:
        print(f"  console: {c[:300]}")


if __name__ == "__main__":
    main()
