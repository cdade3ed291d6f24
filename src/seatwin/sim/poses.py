"""Vessel poses from a scenario, as the recording takes them (:class:`~seatwin.recording.VesselPose`).

:func:`poses_from_scenario` gives one instant; :class:`PoseTable` a whole run's frame times at
once — one vectorised trajectory lookup per vessel and one vectorised NED → WGS-84 conversion of
the ownship's positions (its NavSatFix: :func:`seatwin.geo.geodetic.ned_to_llh_wgs84`, the bits of
``pymap3d`` without its per-call overhead), instead of a ``pymap3d`` call per step (~0.2 ms). Both
give the same values (to float rounding of the vectorised conversion).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo import GeodeticOrigin
from seatwin.geo.geodetic import ned_to_llh_wgs84
from seatwin.recording import VesselPose
from seatwin.scenario import Role, Scenario


def poses_from_scenario(scenario: Scenario, t: float) -> list[VesselPose]:
    """Every vessel's pose at ``t`` (no ``llh``: the writer converts the ownship's with its origin)."""
    out = []
    for v in scenario.vessels:
        s = v.trajectory.state_at(t)
        out.append(
            VesselPose(
                name=v.name,
                north=float(s.north),
                east=float(s.east),
                heading=float(s.heading),
                v_north=float(s.v_north),
                v_east=float(s.v_east),
                yaw_rate=float(s.yaw_rate),
                ownship=v.role == Role.OWNSHIP,
            )
        )
    return out


@dataclass(frozen=True)
class PoseTable:
    """Every vessel's state at fixed ``times``: rows (north, east, heading, v_north, v_east, yaw_rate)
    per vessel, and the ownship's WGS-84 (lat °, lon °, height m) when the origin is known."""

    times: NDArray[np.float64]
    names: tuple[str, ...]
    ownship: tuple[bool, ...]
    states: tuple[NDArray[np.float64], ...]
    """Per vessel: shape (len(times), 6)."""
    llh: tuple[NDArray[np.float64] | None, ...]
    """Per vessel: shape (len(times), 3) for the ownship with an origin, else None."""

    @classmethod
    def from_scenario(cls, scenario: Scenario, times: ArrayLike, origin: GeodeticOrigin | None = None) -> PoseTable:
        """The table at ``times`` (``origin``: default the scenario's)."""
        tt = np.asarray(times, dtype=float).reshape(-1)
        origin = origin if origin is not None else scenario.origin
        names, own, states, llh = [], [], [], []
        for v in scenario.vessels:
            s = v.trajectory.state_at(tt)
            cols = np.column_stack(
                [
                    np.broadcast_to(np.asarray(a, float), tt.shape)
                    for a in (s.north, s.east, s.heading, s.v_north, s.v_east, s.yaw_rate)
                ]
            )
            is_own = v.role == Role.OWNSHIP
            names.append(v.name)
            own.append(is_own)
            states.append(cols)
            if is_own and origin is not None:
                lat, lon, h = ned_to_llh_wgs84(cols[:, 0], cols[:, 1], np.zeros(len(tt)), origin)
                llh.append(np.column_stack([np.broadcast_to(a, tt.shape) for a in (lat, lon, h)]))
            else:
                llh.append(None)
        return cls(tt, tuple(names), tuple(own), tuple(states), tuple(llh))

    def poses(self, k: int) -> list[VesselPose]:
        """Every vessel's pose at ``times[k]``."""
        out = []
        for name, own, st, ll in zip(self.names, self.ownship, self.states, self.llh):
            n, e, h, vn, ve, r = st[k].tolist()
            out.append(
                VesselPose(
                    name=name,
                    north=n,
                    east=e,
                    heading=h,
                    v_north=vn,
                    v_east=ve,
                    yaw_rate=r,
                    ownship=own,
                    llh=None if ll is None else tuple(ll[k].tolist()),
                )
            )
        return out
