from google.protobuf.internal import containers as _containers
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class CameraStreamingRequest(_message.Message):
    __slots__ = ("data", "timeStamp", "width", "height", "frame_id")
    DATA_FIELD_NUMBER: _ClassVar[int]
    TIMESTAMP_FIELD_NUMBER: _ClassVar[int]
    WIDTH_FIELD_NUMBER: _ClassVar[int]
    HEIGHT_FIELD_NUMBER: _ClassVar[int]
    FRAME_ID_FIELD_NUMBER: _ClassVar[int]
    data: bytes
    timeStamp: float
    width: int
    height: int
    frame_id: str
    def __init__(self, data: _Optional[bytes] = ..., timeStamp: _Optional[float] = ..., width: _Optional[int] = ..., height: _Optional[int] = ..., frame_id: _Optional[str] = ...) -> None: ...

class CameraStreamingResponse(_message.Message):
    __slots__ = ("success",)
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    success: bool
    def __init__(self, success: _Optional[bool] = ...) -> None: ...

class Vec3(_message.Message):
    __slots__ = ("x", "y", "z")
    X_FIELD_NUMBER: _ClassVar[int]
    Y_FIELD_NUMBER: _ClassVar[int]
    Z_FIELD_NUMBER: _ClassVar[int]
    x: float
    y: float
    z: float
    def __init__(self, x: _Optional[float] = ..., y: _Optional[float] = ..., z: _Optional[float] = ...) -> None: ...

class PointField(_message.Message):
    __slots__ = ("INT8", "UINT8", "INT16", "UINT16", "INT32", "UINT32", "FLOAT32", "FLOAT64", "name", "offset", "datatype", "count")
    INT8_FIELD_NUMBER: _ClassVar[int]
    UINT8_FIELD_NUMBER: _ClassVar[int]
    INT16_FIELD_NUMBER: _ClassVar[int]
    UINT16_FIELD_NUMBER: _ClassVar[int]
    INT32_FIELD_NUMBER: _ClassVar[int]
    UINT32_FIELD_NUMBER: _ClassVar[int]
    FLOAT32_FIELD_NUMBER: _ClassVar[int]
    FLOAT64_FIELD_NUMBER: _ClassVar[int]
    NAME_FIELD_NUMBER: _ClassVar[int]
    OFFSET_FIELD_NUMBER: _ClassVar[int]
    DATATYPE_FIELD_NUMBER: _ClassVar[int]
    COUNT_FIELD_NUMBER: _ClassVar[int]
    INT8: int
    UINT8: int
    INT16: int
    UINT16: int
    INT32: int
    UINT32: int
    FLOAT32: int
    FLOAT64: int
    name: str
    offset: int
    datatype: int
    count: int
    def __init__(self, INT8: _Optional[int] = ..., UINT8: _Optional[int] = ..., INT16: _Optional[int] = ..., UINT16: _Optional[int] = ..., INT32: _Optional[int] = ..., UINT32: _Optional[int] = ..., FLOAT32: _Optional[int] = ..., FLOAT64: _Optional[int] = ..., name: _Optional[str] = ..., offset: _Optional[int] = ..., datatype: _Optional[int] = ..., count: _Optional[int] = ...) -> None: ...

class LidarStreamingRequest(_message.Message):
    __slots__ = ("timeInSeconds", "height", "width", "fields", "isBigEndian", "point_step", "row_step", "data", "is_dense", "frame_id")
    TIMEINSECONDS_FIELD_NUMBER: _ClassVar[int]
    HEIGHT_FIELD_NUMBER: _ClassVar[int]
    WIDTH_FIELD_NUMBER: _ClassVar[int]
    FIELDS_FIELD_NUMBER: _ClassVar[int]
    ISBIGENDIAN_FIELD_NUMBER: _ClassVar[int]
    POINT_STEP_FIELD_NUMBER: _ClassVar[int]
    ROW_STEP_FIELD_NUMBER: _ClassVar[int]
    DATA_FIELD_NUMBER: _ClassVar[int]
    IS_DENSE_FIELD_NUMBER: _ClassVar[int]
    FRAME_ID_FIELD_NUMBER: _ClassVar[int]
    timeInSeconds: float
    height: int
    width: int
    fields: _containers.RepeatedCompositeFieldContainer[PointField]
    isBigEndian: bool
    point_step: int
    row_step: int
    data: bytes
    is_dense: bool
    frame_id: str
    def __init__(self, timeInSeconds: _Optional[float] = ..., height: _Optional[int] = ..., width: _Optional[int] = ..., fields: _Optional[_Iterable[_Union[PointField, _Mapping]]] = ..., isBigEndian: _Optional[bool] = ..., point_step: _Optional[int] = ..., row_step: _Optional[int] = ..., data: _Optional[bytes] = ..., is_dense: _Optional[bool] = ..., frame_id: _Optional[str] = ...) -> None: ...

class LidarStreamingResponse(_message.Message):
    __slots__ = ("success",)
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    success: bool
    def __init__(self, success: _Optional[bool] = ...) -> None: ...

class RadarStreamingRequest(_message.Message):
    __slots__ = ("rangeIncrement", "rangeStart", "numSamples", "numSpokes", "minIntensity", "maxIntensity", "timeInSeconds", "azimuth", "radarSpokes")
    RANGEINCREMENT_FIELD_NUMBER: _ClassVar[int]
    RANGESTART_FIELD_NUMBER: _ClassVar[int]
    NUMSAMPLES_FIELD_NUMBER: _ClassVar[int]
    NUMSPOKES_FIELD_NUMBER: _ClassVar[int]
    MININTENSITY_FIELD_NUMBER: _ClassVar[int]
    MAXINTENSITY_FIELD_NUMBER: _ClassVar[int]
    TIMEINSECONDS_FIELD_NUMBER: _ClassVar[int]
    AZIMUTH_FIELD_NUMBER: _ClassVar[int]
    RADARSPOKES_FIELD_NUMBER: _ClassVar[int]
    rangeIncrement: float
    rangeStart: float
    numSamples: int
    numSpokes: int
    minIntensity: int
    maxIntensity: int
    timeInSeconds: _containers.RepeatedScalarFieldContainer[float]
    azimuth: _containers.RepeatedScalarFieldContainer[float]
    radarSpokes: bytes
    def __init__(self, rangeIncrement: _Optional[float] = ..., rangeStart: _Optional[float] = ..., numSamples: _Optional[int] = ..., numSpokes: _Optional[int] = ..., minIntensity: _Optional[int] = ..., maxIntensity: _Optional[int] = ..., timeInSeconds: _Optional[_Iterable[float]] = ..., azimuth: _Optional[_Iterable[float]] = ..., radarSpokes: _Optional[bytes] = ...) -> None: ...

class RadarStreamingResponse(_message.Message):
    __slots__ = ("success",)
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    success: bool
    def __init__(self, success: _Optional[bool] = ...) -> None: ...
