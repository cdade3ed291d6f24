from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class GeneralizedForce(_message.Message):
    __slots__ = ("x", "y", "z", "k", "m", "n")
    X_FIELD_NUMBER: _ClassVar[int]
    Y_FIELD_NUMBER: _ClassVar[int]
    Z_FIELD_NUMBER: _ClassVar[int]
    K_FIELD_NUMBER: _ClassVar[int]
    M_FIELD_NUMBER: _ClassVar[int]
    N_FIELD_NUMBER: _ClassVar[int]
    x: float
    y: float
    z: float
    k: float
    m: float
    n: float
    def __init__(self, x: _Optional[float] = ..., y: _Optional[float] = ..., z: _Optional[float] = ..., k: _Optional[float] = ..., m: _Optional[float] = ..., n: _Optional[float] = ...) -> None: ...

class ForceRequest(_message.Message):
    __slots__ = ("vesselId", "generalizedForce")
    VESSELID_FIELD_NUMBER: _ClassVar[int]
    GENERALIZEDFORCE_FIELD_NUMBER: _ClassVar[int]
    vesselId: str
    generalizedForce: GeneralizedForce
    def __init__(self, vesselId: _Optional[str] = ..., generalizedForce: _Optional[_Union[GeneralizedForce, _Mapping]] = ...) -> None: ...

class ForceResponse(_message.Message):
    __slots__ = ("success",)
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    success: bool
    def __init__(self, success: _Optional[bool] = ...) -> None: ...
