"""How many points a cluster's tile holds: the default and the check of a given value (one home for the
command, ``lod_files`` and ``copc_file``)."""
from __future__ import annotations

from .errors import InputError

DEFAULT = 2_000_000  # about 0.4 GB of domain a tile (docs/array_memory.md): a worker holds one beside its halo
MINIMUM = 1000       # below this the halo would outweigh the tile


def checked(tile_points, name: str = "tile_points") -> int:
    """tile_points, or InputError naming it as `name` (the command's option, the functions' argument)."""
    if isinstance(tile_points, bool) or not isinstance(tile_points, int) or tile_points < MINIMUM:
        raise InputError(f"{name} must be a whole number of at least {MINIMUM:,}, got {tile_points!r}")
    return tile_points
