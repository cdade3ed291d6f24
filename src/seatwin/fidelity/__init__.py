"""The thesis's fidelity method (ch. 5.2) on real data: real versus synthetic, same tracker, AHED.

* :func:`seatwin.fidelity.method.run_fidelity` — the joyride method end to end → :class:`FidelityResult`.
* :class:`FidelityOptions` — every choice of a run (:mod:`.options`).
* :func:`seatwin.fidelity.report.write_fidelity` — ``fidelity.json``, ``fidelity.md``, ``index.html``.
* :mod:`seatwin.fidelity.joyride` — the dataset and its synthetic replica.
* :mod:`seatwin.fidelity.ablations` — deliberately wrong radar models, ranked below the fitted one by the score.
"""

from seatwin.fidelity.method import run_fidelity
from seatwin.fidelity.options import FidelityOptions
from seatwin.fidelity.report import write_fidelity
from seatwin.fidelity.results import AgentResult, FidelityResult, ModelResult

__all__ = ["AgentResult", "FidelityOptions", "FidelityResult", "ModelResult", "run_fidelity", "write_fidelity"]
