"""``geo`` is a leaf: importing it loads no other seatwin module (nor pymap3d, until an exact conversion runs)."""

from __future__ import annotations

import json
import subprocess
import sys


def _loaded_after(statement: str) -> list[str]:
    code = f"import json, sys; {statement}; print(json.dumps(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def test_import_geo_loads_no_other_seatwin_module() -> None:
    loaded = _loaded_after("import seatwin.geo")
    others = [m for m in loaded if m.startswith("seatwin") and m != "seatwin" and not m.startswith("seatwin.geo")]
    assert others == []
    assert "seatwin.geo.frames" in loaded and "seatwin.geo.angles" in loaded
    assert "pymap3d" not in loaded  # 0.15 s to import: only inside the exact conversions
