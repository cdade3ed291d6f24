from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class Vec3(_message.Message):
    __slots__ = ("x", "y", "z")
    X_FIELD_NUMBER: _ClassVar[int]
    Y_FIELD_NUMBER: _ClassVar[int]
    Z_FIELD_NUMBER: _ClassVar[int]
    x: float
    y: float
    z: float
    def __init__(self, x: _Optional[float] = ..., y: _Optional[float] = ..., z: _Optional[float] = ...) -> None: ...

class Quaternion(_message.Message):
    __slots__ = ("x", "y", "z", "w")
    X_FIELD_NUMBER: _ClassVar[int]
    Y_FIELD_NUMBER: _ClassVar[int]
    Z_FIELD_NUMBER: _ClassVar[int]
    W_FIELD_NUMBER: _ClassVar[int]
    x: float
    y: float
    z: float
    w: float
    def __init__(self, x: _Optional[float] = ..., y: _Optional[float] = ..., z: _Optional[float] = ..., w: _Optional[float] = ...) -> None: ...

class NavigationRequest(_message.Message):
    __slots__ = ("timeStamp", "position", "orientation", "linearVelocity", "angularVelocity", "vesselName")
    TIMESTAMP_FIELD_NUMBER: _ClassVar[int]
    POSITION_FIELD_NUMBER: _ClassVar[int]
    ORIENTATION_FIELD_NUMBER: _ClassVar[int]
    LINEARVELOCITY_FIELD_NUMBER: _ClassVar[int]
    ANGULARVELOCITY_FIELD_NUMBER: _ClassVar[int]
    VESSELNAME_FIELD_NUMBER: _ClassVar[int]
    timeStamp: float
    position: Vec3
    orientation: Quaternion
    linearVelocity: Vec3
    angularVelocity: Vec3
    vesselName: str
    def __init__(self, timeStamp: _Optional[float] = ..., position: _Optional[_Union[Vec3, _Mapping]] = ..., orientation: _Optional[_Union[Quaternion, _Mapping]] = ..., linearVelocity: _Optional[_Union[Vec3, _Mapping]] = ..., angularVelocity: _Optional[_Union[Vec3, _Mapping]] = ..., vesselName: _Optional[str] = ...) -> None: ...

class NavigationResponse(_message.Message):
    __slots__ = ("success",)
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    success: bool
    def __init__(self, success: _Optional[bool] = ...) -> None: ...
