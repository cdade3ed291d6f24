"""A harbour's moored boats: read from its file, placed in the scenario frame, exposed as positions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.errors import InputError
from seatwin.layout import DEFAULT_LAYOUT, LandRaster, harbour_map, harbour_moored_boats, moored_boat_positions
from seatwin.layout.alignment import Alignment
from seatwin.layout.harbours import RAVNKLOA_MOORED, read_moored_boats
from seatwin.layout.model import MooredBoat


def _footprint(b: MooredBoat) -> np.ndarray:
    h = math.radians(b.heading_deg)
    pts = []
    for a in (-0.5, 0.5):
        for s in (-0.5, 0.5):
            pts.append(
                (
                    b.north + a * b.length * math.cos(h) - s * b.beam * math.sin(h),
                    b.east + a * b.length * math.sin(h) + s * b.beam * math.cos(h),
                )
            )
    return np.asarray(pts)


def test_positions_of_the_default_harbour_and_of_a_run_hint() -> None:
    pos = moored_boat_positions("harbour")  # a run's water-mask hint for the built-in harbour
    assert pos.shape == (len(DEFAULT_LAYOUT.moored_boats), 2)
    assert pos[0].tolist() == [DEFAULT_LAYOUT.moored_boats[0].north, DEFAULT_LAYOUT.moored_boats[0].east]
    assert moored_boat_positions("none").shape == (0, 2)


def test_raster_moored_boats_follow_the_alignment() -> None:
    boat = MooredBoat("b", 10.0, 0.0, 0.0, 6.0, 2.0, 1.5)
    r = LandRaster(np.ones((4, 4), bool), 0.0, 0.0, moored_boats=(boat,)).aligned(Alignment(90.0))
    (moved,) = r.moored()
    # scenario → map turns 90° clockwise, so map → scenario turns a point north of the origin to its west
    assert (moved.north, moved.east, moved.heading_deg) == pytest.approx((0.0, -10.0, -90.0))
    assert r.is_water(*r.alignment.to_map(moved.north, moved.east))


def test_bad_moored_boat_files(tmp_path) -> None:
    p = tmp_path / "m.yaml"
    p.write_text("moored_boats:\n  - {name: a, north: 1, east: 2}\n")
    with pytest.raises(InputError, match=r"moored_boats\[0\]: expected the keys name, north, east"):
        read_moored_boats(p)
    p.write_text("moored_boats:\n  - {name: a, north: x, east: 2, heading_deg: 0, length: 3, beam: 1, height: 1}\n")
    with pytest.raises(InputError, match="expected numbers"):
        read_moored_boats(p)
    p.write_text("boats: []\n")
    with pytest.raises(InputError, match="a list 'moored_boats'"):
        read_moored_boats(p)


@pytest.mark.slow
def test_ravnkloa_moored_boats_lie_on_water_along_a_quay(shared_data) -> None:
    from scipy.ndimage import distance_transform_edt

    from seatwin.scenario.load import load_scenario
    from seatwin.world.scene import Scene

    assert len(read_moored_boats(RAVNKLOA_MOORED)) == 5
    raster = harbour_map("ravnkloa")
    assert isinstance(raster, LandRaster)
    boats = harbour_moored_boats("ravnkloa")
    to_land = distance_transform_edt(raster.water)
    paths = [
        np.c_[v.trajectory.north, v.trajectory.east]
        for k in (3, 4, 5, 6)
        for v in load_scenario(shared_data / "gemini-scenarios" / f"Scenario{k}.csv").vessels
    ]
    for b in boats:
        corners = _footprint(b)
        assert raster.is_water(corners[:, 0], corners[:, 1], outside=False).all(), b.name
        n, e = raster.alignment.to_map(b.north, b.east)
        r, c = int((n - raster.origin_north) // 1), int((e - raster.origin_east) // 1)
        assert to_land[r, c] <= b.beam / 2 + 3.0, b.name  # alongside a quay
        assert min(np.hypot(*(p - [b.north, b.east]).T).min() for p in paths) > 10.0  # clear of every Gemini vessel
    sc = load_scenario(shared_data / "gemini-scenarios" / "Scenario6.csv")
    assert set(Scene.from_scenario(sc).moored_boats) == {b.name for b in boats}


_values = st.one_of(
    st.none(), st.booleans(), st.integers(), st.floats(allow_nan=True), st.text(max_size=5), st.lists(st.integers(), max_size=2)
)


@settings(max_examples=80, deadline=None)
@given(
    st.one_of(
        st.text(max_size=60),
        st.dictionaries(
            st.sampled_from(["moored_boats", "rotation_deg", "shift_east", "x"]),
            _values
            | st.lists(
                st.dictionaries(st.sampled_from(["name", "north", "east", "heading_deg", "length", "beam", "height"]), _values),
                max_size=2,
            ),
            max_size=3,
        ),
    )
)
def test_hostile_harbour_files_are_read_or_refused_with_an_input_error(tmp_path_factory, content) -> None:
    """Any file content: the alignment and moored-boat readers return data or raise one InputError."""
    import yaml

    from seatwin.layout.alignment import read_alignment

    p = tmp_path_factory.mktemp("h") / "f.yaml"
    p.write_text(content if isinstance(content, str) else yaml.safe_dump(content))
    for reader in (read_alignment, read_moored_boats):
        try:
            reader(p)
        except InputError as exc:
            assert str(p) in str(exc)
