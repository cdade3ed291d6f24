from seatwin.api.proto import navigation_pb2 as _navigation_pb2
from seatwin.api.proto import sensor_streaming_pb2 as _sensor_streaming_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class ObserveRequest(_message.Message):
    __slots__ = ("agent",)
    AGENT_FIELD_NUMBER: _ClassVar[int]
    agent: str
    def __init__(self, agent: _Optional[str] = ...) -> None: ...

class Observation(_message.Message):
    __slots__ = ("mission", "step", "finished")
    MISSION_FIELD_NUMBER: _ClassVar[int]
    STEP_FIELD_NUMBER: _ClassVar[int]
    FINISHED_FIELD_NUMBER: _ClassVar[int]
    mission: Mission
    step: Step
    finished: Finished
    def __init__(self, mission: _Optional[_Union[Mission, _Mapping]] = ..., step: _Optional[_Union[Step, _Mapping]] = ..., finished: _Optional[_Union[Finished, _Mapping]] = ...) -> None: ...

class Mission(_message.Message):
    __slots__ = ("start_north", "start_east", "goal_north", "goal_east", "cruise_speed", "harbour", "length", "beam", "vessel_id", "sensors")
    START_NORTH_FIELD_NUMBER: _ClassVar[int]
    START_EAST_FIELD_NUMBER: _ClassVar[int]
    GOAL_NORTH_FIELD_NUMBER: _ClassVar[int]
    GOAL_EAST_FIELD_NUMBER: _ClassVar[int]
    CRUISE_SPEED_FIELD_NUMBER: _ClassVar[int]
    HARBOUR_FIELD_NUMBER: _ClassVar[int]
    LENGTH_FIELD_NUMBER: _ClassVar[int]
    BEAM_FIELD_NUMBER: _ClassVar[int]
    VESSEL_ID_FIELD_NUMBER: _ClassVar[int]
    SENSORS_FIELD_NUMBER: _ClassVar[int]
    start_north: float
    start_east: float
    goal_north: float
    goal_east: float
    cruise_speed: float
    harbour: str
    length: float
    beam: float
    vessel_id: str
    sensors: _containers.RepeatedScalarFieldContainer[str]
    def __init__(self, start_north: _Optional[float] = ..., start_east: _Optional[float] = ..., goal_north: _Optional[float] = ..., goal_east: _Optional[float] = ..., cruise_speed: _Optional[float] = ..., harbour: _Optional[str] = ..., length: _Optional[float] = ..., beam: _Optional[float] = ..., vessel_id: _Optional[str] = ..., sensors: _Optional[_Iterable[str]] = ...) -> None: ...

class State(_message.Message):
    __slots__ = ("time", "north", "east", "heading", "u", "v", "r")
    TIME_FIELD_NUMBER: _ClassVar[int]
    NORTH_FIELD_NUMBER: _ClassVar[int]
    EAST_FIELD_NUMBER: _ClassVar[int]
    HEADING_FIELD_NUMBER: _ClassVar[int]
    U_FIELD_NUMBER: _ClassVar[int]
    V_FIELD_NUMBER: _ClassVar[int]
    R_FIELD_NUMBER: _ClassVar[int]
    time: float
    north: float
    east: float
    heading: float
    u: float
    v: float
    r: float
    def __init__(self, time: _Optional[float] = ..., north: _Optional[float] = ..., east: _Optional[float] = ..., heading: _Optional[float] = ..., u: _Optional[float] = ..., v: _Optional[float] = ..., r: _Optional[float] = ...) -> None: ...

class Target(_message.Message):
    __slots__ = ("name", "north", "east", "v_north", "v_east", "length", "beam")
    NAME_FIELD_NUMBER: _ClassVar[int]
    NORTH_FIELD_NUMBER: _ClassVar[int]
    EAST_FIELD_NUMBER: _ClassVar[int]
    V_NORTH_FIELD_NUMBER: _ClassVar[int]
    V_EAST_FIELD_NUMBER: _ClassVar[int]
    LENGTH_FIELD_NUMBER: _ClassVar[int]
    BEAM_FIELD_NUMBER: _ClassVar[int]
    name: str
    north: float
    east: float
    v_north: float
    v_east: float
    length: float
    beam: float
    def __init__(self, name: _Optional[str] = ..., north: _Optional[float] = ..., east: _Optional[float] = ..., v_north: _Optional[float] = ..., v_east: _Optional[float] = ..., length: _Optional[float] = ..., beam: _Optional[float] = ...) -> None: ...

class TruthFrame(_message.Message):
    __slots__ = ("targets",)
    TARGETS_FIELD_NUMBER: _ClassVar[int]
    targets: _containers.RepeatedCompositeFieldContainer[Target]
    def __init__(self, targets: _Optional[_Iterable[_Union[Target, _Mapping]]] = ...) -> None: ...

class Frame(_message.Message):
    __slots__ = ("sensor", "time", "navigation", "truth", "lidar", "radar", "mount")
    SENSOR_FIELD_NUMBER: _ClassVar[int]
    TIME_FIELD_NUMBER: _ClassVar[int]
    NAVIGATION_FIELD_NUMBER: _ClassVar[int]
    TRUTH_FIELD_NUMBER: _ClassVar[int]
    LIDAR_FIELD_NUMBER: _ClassVar[int]
    RADAR_FIELD_NUMBER: _ClassVar[int]
    MOUNT_FIELD_NUMBER: _ClassVar[int]
    sensor: str
    time: float
    navigation: State
    truth: TruthFrame
    lidar: _sensor_streaming_pb2.LidarStreamingRequest
    radar: RadarPlots
    mount: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, sensor: _Optional[str] = ..., time: _Optional[float] = ..., navigation: _Optional[_Union[State, _Mapping]] = ..., truth: _Optional[_Union[TruthFrame, _Mapping]] = ..., lidar: _Optional[_Union[_sensor_streaming_pb2.LidarStreamingRequest, _Mapping]] = ..., radar: _Optional[_Union[RadarPlots, _Mapping]] = ..., mount: _Optional[_Iterable[float]] = ...) -> None: ...

class RadarPlots(_message.Message):
    __slots__ = ("antenna_north", "antenna_east", "antenna_heading", "antenna_height", "range", "azimuth", "north", "east", "cells", "extent", "intensity")
    ANTENNA_NORTH_FIELD_NUMBER: _ClassVar[int]
    ANTENNA_EAST_FIELD_NUMBER: _ClassVar[int]
    ANTENNA_HEADING_FIELD_NUMBER: _ClassVar[int]
    ANTENNA_HEIGHT_FIELD_NUMBER: _ClassVar[int]
    RANGE_FIELD_NUMBER: _ClassVar[int]
    AZIMUTH_FIELD_NUMBER: _ClassVar[int]
    NORTH_FIELD_NUMBER: _ClassVar[int]
    EAST_FIELD_NUMBER: _ClassVar[int]
    CELLS_FIELD_NUMBER: _ClassVar[int]
    EXTENT_FIELD_NUMBER: _ClassVar[int]
    INTENSITY_FIELD_NUMBER: _ClassVar[int]
    antenna_north: float
    antenna_east: float
    antenna_heading: float
    antenna_height: float
    range: _containers.RepeatedScalarFieldContainer[float]
    azimuth: _containers.RepeatedScalarFieldContainer[float]
    north: _containers.RepeatedScalarFieldContainer[float]
    east: _containers.RepeatedScalarFieldContainer[float]
    cells: _containers.RepeatedScalarFieldContainer[int]
    extent: _containers.RepeatedScalarFieldContainer[float]
    intensity: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, antenna_north: _Optional[float] = ..., antenna_east: _Optional[float] = ..., antenna_heading: _Optional[float] = ..., antenna_height: _Optional[float] = ..., range: _Optional[_Iterable[float]] = ..., azimuth: _Optional[_Iterable[float]] = ..., north: _Optional[_Iterable[float]] = ..., east: _Optional[_Iterable[float]] = ..., cells: _Optional[_Iterable[int]] = ..., extent: _Optional[_Iterable[float]] = ..., intensity: _Optional[_Iterable[float]] = ...) -> None: ...

class Step(_message.Message):
    __slots__ = ("index", "time", "own", "navigation", "frames")
    INDEX_FIELD_NUMBER: _ClassVar[int]
    TIME_FIELD_NUMBER: _ClassVar[int]
    OWN_FIELD_NUMBER: _ClassVar[int]
    NAVIGATION_FIELD_NUMBER: _ClassVar[int]
    FRAMES_FIELD_NUMBER: _ClassVar[int]
    index: int
    time: float
    own: State
    navigation: _navigation_pb2.NavigationRequest
    frames: _containers.RepeatedCompositeFieldContainer[Frame]
    def __init__(self, index: _Optional[int] = ..., time: _Optional[float] = ..., own: _Optional[_Union[State, _Mapping]] = ..., navigation: _Optional[_Union[_navigation_pb2.NavigationRequest, _Mapping]] = ..., frames: _Optional[_Iterable[_Union[Frame, _Mapping]]] = ...) -> None: ...

class Finished(_message.Message):
    __slots__ = ("reason",)
    REASON_FIELD_NUMBER: _ClassVar[int]
    reason: str
    def __init__(self, reason: _Optional[str] = ...) -> None: ...

class Track(_message.Message):
    __slots__ = ("id", "north", "east", "v_north", "v_east")
    ID_FIELD_NUMBER: _ClassVar[int]
    NORTH_FIELD_NUMBER: _ClassVar[int]
    EAST_FIELD_NUMBER: _ClassVar[int]
    V_NORTH_FIELD_NUMBER: _ClassVar[int]
    V_EAST_FIELD_NUMBER: _ClassVar[int]
    id: int
    north: float
    east: float
    v_north: float
    v_east: float
    def __init__(self, id: _Optional[int] = ..., north: _Optional[float] = ..., east: _Optional[float] = ..., v_north: _Optional[float] = ..., v_east: _Optional[float] = ...) -> None: ...

class VelocityRequest(_message.Message):
    __slots__ = ("step", "speed", "heading", "tracks")
    STEP_FIELD_NUMBER: _ClassVar[int]
    SPEED_FIELD_NUMBER: _ClassVar[int]
    HEADING_FIELD_NUMBER: _ClassVar[int]
    TRACKS_FIELD_NUMBER: _ClassVar[int]
    step: int
    speed: float
    heading: float
    tracks: _containers.RepeatedCompositeFieldContainer[Track]
    def __init__(self, step: _Optional[int] = ..., speed: _Optional[float] = ..., heading: _Optional[float] = ..., tracks: _Optional[_Iterable[_Union[Track, _Mapping]]] = ...) -> None: ...

class ForceRequest(_message.Message):
    __slots__ = ("step", "x", "y", "n", "tracks")
    STEP_FIELD_NUMBER: _ClassVar[int]
    X_FIELD_NUMBER: _ClassVar[int]
    Y_FIELD_NUMBER: _ClassVar[int]
    N_FIELD_NUMBER: _ClassVar[int]
    TRACKS_FIELD_NUMBER: _ClassVar[int]
    step: int
    x: float
    y: float
    n: float
    tracks: _containers.RepeatedCompositeFieldContainer[Track]
    def __init__(self, step: _Optional[int] = ..., x: _Optional[float] = ..., y: _Optional[float] = ..., n: _Optional[float] = ..., tracks: _Optional[_Iterable[_Union[Track, _Mapping]]] = ...) -> None: ...

class ThrustRequest(_message.Message):
    __slots__ = ("step", "angles", "thrusts", "tracks")
    STEP_FIELD_NUMBER: _ClassVar[int]
    ANGLES_FIELD_NUMBER: _ClassVar[int]
    THRUSTS_FIELD_NUMBER: _ClassVar[int]
    TRACKS_FIELD_NUMBER: _ClassVar[int]
    step: int
    angles: _containers.RepeatedScalarFieldContainer[float]
    thrusts: _containers.RepeatedScalarFieldContainer[float]
    tracks: _containers.RepeatedCompositeFieldContainer[Track]
    def __init__(self, step: _Optional[int] = ..., angles: _Optional[_Iterable[float]] = ..., thrusts: _Optional[_Iterable[float]] = ..., tracks: _Optional[_Iterable[_Union[Track, _Mapping]]] = ...) -> None: ...

class Action(_message.Message):
    __slots__ = ("velocity", "force", "thrust")
    VELOCITY_FIELD_NUMBER: _ClassVar[int]
    FORCE_FIELD_NUMBER: _ClassVar[int]
    THRUST_FIELD_NUMBER: _ClassVar[int]
    velocity: VelocityRequest
    force: ForceRequest
    thrust: ThrustRequest
    def __init__(self, velocity: _Optional[_Union[VelocityRequest, _Mapping]] = ..., force: _Optional[_Union[ForceRequest, _Mapping]] = ..., thrust: _Optional[_Union[ThrustRequest, _Mapping]] = ...) -> None: ...

class CommandResponse(_message.Message):
    __slots__ = ("success",)
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    success: bool
    def __init__(self, success: _Optional[bool] = ...) -> None: ...
