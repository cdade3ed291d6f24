"""Gemini-compatible gRPC services (thesis Fig. 4.17): the ``Simulation`` server that seatwin runs in
lock-step with an OSP scenario generator, and the ``SensorStreaming``/``Navigation`` client and server.

The wire format is Gemini's (:mod:`seatwin.api.proto`); see docs/architecture/cosim.md.
"""
