"""slender's Python side: run decks (slender.run), read their dumps (slender.io) and draw
them (slender.plot). `python3 -m slender --help` for the command line."""

from .run import RunResult, find_binary, parse_results, run_deck

__version__ = "0.1.0"

_IO_NAMES = {"Checkpoint", "Surface", "Trajectory", "open_dump", "read_checkpoint"}

__all__ = ["RunResult", "find_binary", "parse_results", "run_deck", "__version__", *sorted(_IO_NAMES)]


def __getattr__(name):
    """slender.io's readers, imported on first use: running decks needs neither numpy nor h5py."""
    if name in _IO_NAMES:
        from . import io
        return getattr(io, name)
    raise AttributeError(f"module 'slender' has no attribute {name!r}")
