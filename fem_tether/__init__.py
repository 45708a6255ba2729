"""fem-tether: flexible-tether drag and annual energy of two-line AWE systems."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("fem-tether")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0+unknown"
