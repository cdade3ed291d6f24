"""``seatwin view``: a recorded run served to Foxglove (WebSocket), played in a loop."""

from __future__ import annotations

from pathlib import Path

import typer


def register(app: typer.Typer) -> None:
    @app.command("view")
    def view_cmd(
        run: Path = typer.Argument(..., help="A run directory, a rosbag2 directory, or a .mcap, .db3 or .bag file."),
        port: int = typer.Option(8765, "--port", help="WebSocket port (Foxglove's default 8765; 0: any free one)."),
        host: str = typer.Option("127.0.0.1", "--host", help="Address to listen on (default loopback only)."),
        speed: float = typer.Option(1.0, "--speed", help="Playback speed (× real time; 0: as fast as possible)."),
    ) -> None:
        """Serve a run to Foxglove over its WebSocket protocol, played in a loop until Ctrl-C.

        In Foxglove: Open connection → Foxglove WebSocket → ws://127.0.0.1:8765, then import
        docs/foxglove/seatwin-layout.json for the cameras with their boxes, the cloud, the radar and the vessels.
        """
        import threading

        from seatwin.errors import ParameterError
        from seatwin.interrupts import interrupts_set_event, wait
        from seatwin.recording.view import RecordingViewer

        if speed < 0:
            raise ParameterError("speed", f"expected ≥ 0 (0: as fast as possible), got {speed}")
        stop = threading.Event()
        with interrupts_set_event() as signalled, RecordingViewer(run, host=host, port=port) as viewer:
            bound = viewer.start()
            typer.echo(f"serving {len(viewer.messages)} messages of {run} to Foxglove on ws://{host}:{bound} (Ctrl-C to stop)")
            worker = threading.Thread(target=viewer.play_loop, args=(speed, stop), name="seatwin-view", daemon=True)
            worker.start()
            try:
                wait(signalled)
            finally:
                stop.set()
                worker.join()
