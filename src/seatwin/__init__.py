"""seatwin — a digital twin framework for testing how autonomous ships perceive the world."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("seatwin")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.0.0+unknown"
