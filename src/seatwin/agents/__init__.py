"""Agents under test: the interface every transport speaks (:mod:`.interface`), and the reference agent —
perception in process (:mod:`.perception`), COLREG velocity obstacles and LOS guidance (:mod:`.avoidance`), its
variants (:mod:`.reference`: ``reference``, ``perfect``, ``late``)."""

from seatwin.agents.avoidance import AvoidanceParameters, choose_velocity, los_guidance
from seatwin.agents.interface import (
    Agent,
    Command,
    ForceCommand,
    Mission,
    Navigation,
    SensorFrame,
    SetPoint,
    ThrusterCommand,
    TrackEstimate,
    TruthTarget,
)
from seatwin.agents.reference import VARIANTS, ReferenceAgent, make_agent

__all__ = [
    "VARIANTS",
    "Agent",
    "AvoidanceParameters",
    "Command",
    "ForceCommand",
    "Mission",
    "Navigation",
    "ReferenceAgent",
    "SensorFrame",
    "SetPoint",
    "ThrusterCommand",
    "TrackEstimate",
    "TruthTarget",
    "choose_velocity",
    "los_guidance",
    "make_agent",
]
