"""Frames (parallel HDF5, ParaView-readable) and diagnostics."""

from .frames import list_frames, read_frame

__all__ = ["list_frames", "read_frame"]
