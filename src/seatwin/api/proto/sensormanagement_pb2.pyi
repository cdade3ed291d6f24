from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class SensorType(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    UNKNOWN: _ClassVar[SensorType]
    OPTICAL: _ClassVar[SensorType]
    INFRARED: _ClassVar[SensorType]
    RADAR: _ClassVar[SensorType]
    LIDAR: _ClassVar[SensorType]
UNKNOWN: SensorType
OPTICAL: SensorType
INFRARED: SensorType
RADAR: SensorType
LIDAR: SensorType

class StartRenderingRequest(_message.Message):
    __slots__ = ("sensorID",)
    SENSORID_FIELD_NUMBER: _ClassVar[int]
    sensorID: int
    def __init__(self, sensorID: _Optional[int] = ...) -> None: ...

class StartRenderingResponse(_message.Message):
    __slots__ = ("success",)
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    success: bool
    def __init__(self, success: _Optional[bool] = ...) -> None: ...

class StopRenderingRequest(_message.Message):
    __slots__ = ("sensorID",)
    SENSORID_FIELD_NUMBER: _ClassVar[int]
    sensorID: int
    def __init__(self, sensorID: _Optional[int] = ...) -> None: ...

class StopRenderingResponse(_message.Message):
    __slots__ = ("success",)
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    success: bool
    def __init__(self, success: _Optional[bool] = ...) -> None: ...

class AllSensorsOfTypeRequest(_message.Message):
    __slots__ = ("type",)
    TYPE_FIELD_NUMBER: _ClassVar[int]
    type: SensorType
    def __init__(self, type: _Optional[_Union[SensorType, str]] = ...) -> None: ...

class AllSensorsOfTypeResponse(_message.Message):
    __slots__ = ("sensors",)
    SENSORS_FIELD_NUMBER: _ClassVar[int]
    sensors: _containers.RepeatedCompositeFieldContainer[Sensor]
    def __init__(self, sensors: _Optional[_Iterable[_Union[Sensor, _Mapping]]] = ...) -> None: ...

class AllSensorsOnVesselRequest(_message.Message):
    __slots__ = ("vesselID",)
    VESSELID_FIELD_NUMBER: _ClassVar[int]
    vesselID: str
    def __init__(self, vesselID: _Optional[str] = ...) -> None: ...

class AllSensorsOnVesselResponse(_message.Message):
    __slots__ = ("sensors",)
    SENSORS_FIELD_NUMBER: _ClassVar[int]
    sensors: _containers.RepeatedCompositeFieldContainer[Sensor]
    def __init__(self, sensors: _Optional[_Iterable[_Union[Sensor, _Mapping]]] = ...) -> None: ...

class Sensor(_message.Message):
    __slots__ = ("id", "type", "sensorWidth", "sensorHeight", "ipAddress", "port")
    ID_FIELD_NUMBER: _ClassVar[int]
    TYPE_FIELD_NUMBER: _ClassVar[int]
    SENSORWIDTH_FIELD_NUMBER: _ClassVar[int]
    SENSORHEIGHT_FIELD_NUMBER: _ClassVar[int]
    IPADDRESS_FIELD_NUMBER: _ClassVar[int]
    PORT_FIELD_NUMBER: _ClassVar[int]
    id: int
    type: SensorType
    sensorWidth: int
    sensorHeight: int
    ipAddress: str
    port: int
    def __init__(self, id: _Optional[int] = ..., type: _Optional[_Union[SensorType, str]] = ..., sensorWidth: _Optional[int] = ..., sensorHeight: _Optional[int] = ..., ipAddress: _Optional[str] = ..., port: _Optional[int] = ...) -> None: ...
