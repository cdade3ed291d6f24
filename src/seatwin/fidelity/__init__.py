"""The thesis's fidelity method (ch. 5.2) on real data: real versus synthetic, same tracker, AHED.

* :func:`seatwin.fidelity.method.run_fidelity` — the joyride method end to end.
* :func:`seatwin.fidelity.report.write_fidelity` — ``fidelity.json``, ``fidelity.md``, ``index.html``.
* :mod:`seatwin.fidelity.joyride` — the dataset and its synthetic replica.
"""

from seatwin.fidelity.method import FidelityOptions, fidelity_json, run_fidelity
from seatwin.fidelity.report import write_fidelity

__all__ = ["FidelityOptions", "fidelity_json", "run_fidelity", "write_fidelity"]
