"""Generated COLREG encounters: geometry (CPA, TCPA, relative course, speeds without avoidance), parameter spaces and
samplers (random, Latin hypercube, adaptive falsification), placement on water, and scenarios saved as files.

* :mod:`.geometry` — :class:`TargetGeometry`, :func:`target_start`, :func:`situation` (COLREG sectors);
* :mod:`.space` — :class:`Encounter`, :class:`EncounterSpace`, :data:`SPACES`, samplers, :func:`adaptive_search`;
* :mod:`.search` — :func:`surrogate_search` (Gaussian-process falsification);
* :mod:`.place` — :func:`place` (open water or a harbour's water, :data:`ENCOUNTER_AREAS`), :func:`paths`;
* :mod:`.build` — :func:`encounter_scenario`, :func:`save_encounter`.
"""

from seatwin.encounters.build import describe, encounter_scenario, save_encounter
from seatwin.encounters.geometry import Kind, TargetGeometry, classify, closest_approach, situation, target_start
from seatwin.encounters.place import ENCOUNTER_AREAS, EncounterPaths, NoPlacementError, Placement, paths, place
from seatwin.encounters.search import surrogate_search
from seatwin.encounters.space import (
    RANGES,
    SPACES,
    Encounter,
    EncounterSpace,
    Trial,
    adaptive_search,
    latin_hypercube,
    random_points,
    space,
)

__all__ = [
    "ENCOUNTER_AREAS",
    "RANGES",
    "SPACES",
    "Encounter",
    "EncounterPaths",
    "EncounterSpace",
    "Kind",
    "NoPlacementError",
    "Placement",
    "TargetGeometry",
    "Trial",
    "adaptive_search",
    "classify",
    "closest_approach",
    "describe",
    "encounter_scenario",
    "latin_hypercube",
    "place",
    "paths",
    "random_points",
    "save_encounter",
    "situation",
    "space",
    "surrogate_search",
    "target_start",
]
