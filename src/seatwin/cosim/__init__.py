"""OSP/FMI co-simulation: the ScenarioPlayer and GeminiBridge FMUs (``pythonfmu``), the OSP system
structure, and running it with ``libcosimpy`` against seatwin's Gemini ``Simulation`` server."""
