"""Closed-loop verification: the lock-step loop of agent, dynamics and simulated sensors (:mod:`.loop`) and the
safety verdict of a run (:mod:`.verdict`) and its continuous robustness (:mod:`.robustness`)."""

from seatwin.verification.loop import GrowingTrack, RunRecord, mission_from, run_closed_loop
from seatwin.verification.robustness import robustness, time_to_breach
from seatwin.verification.verdict import Verdict, VerdictRules, hulls_overlap, judge

__all__ = [
    "GrowingTrack",
    "RunRecord",
    "Verdict",
    "VerdictRules",
    "hulls_overlap",
    "judge",
    "mission_from",
    "robustness",
    "run_closed_loop",
    "time_to_breach",
]
