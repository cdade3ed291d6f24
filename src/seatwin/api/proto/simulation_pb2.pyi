from google.protobuf.internal import containers as _containers
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class Pose(_message.Message):
    __slots__ = ("north", "east", "heading")
    NORTH_FIELD_NUMBER: _ClassVar[int]
    EAST_FIELD_NUMBER: _ClassVar[int]
    HEADING_FIELD_NUMBER: _ClassVar[int]
    north: float
    east: float
    heading: float
    def __init__(self, north: _Optional[float] = ..., east: _Optional[float] = ..., heading: _Optional[float] = ...) -> None: ...

class StepRequest(_message.Message):
    __slots__ = ("VesselPoses", "time", "stepSize")
    VESSELPOSES_FIELD_NUMBER: _ClassVar[int]
    TIME_FIELD_NUMBER: _ClassVar[int]
    STEPSIZE_FIELD_NUMBER: _ClassVar[int]
    VesselPoses: _containers.RepeatedCompositeFieldContainer[Pose]
    time: float
    stepSize: float
    def __init__(self, VesselPoses: _Optional[_Iterable[_Union[Pose, _Mapping]]] = ..., time: _Optional[float] = ..., stepSize: _Optional[float] = ...) -> None: ...

class StepResponse(_message.Message):
    __slots__ = ("success",)
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    success: bool
    def __init__(self, success: _Optional[bool] = ...) -> None: ...

class SetStartTimeRequest(_message.Message):
    __slots__ = ("time",)
    TIME_FIELD_NUMBER: _ClassVar[int]
    time: str
    def __init__(self, time: _Optional[str] = ...) -> None: ...

class SetStartTimeResponse(_message.Message):
    __slots__ = ("success",)
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    success: bool
    def __init__(self, success: _Optional[bool] = ...) -> None: ...
