"""The output folder of a cluster run, which the tool owns only where it wrote.

``index.json`` is the one record of what the tool wrote there: the LOD (tiles, levels, bounds, CRS) and
``owned``, the run folders it made. A run refuses a folder holding anything else (files of the user's,
links, an input), writes into a new run folder beside the last complete one, and replaces the index in
one rename when complete: an interrupted or failed rerun leaves the previous LOD whole. The old run
folders are removed afterwards, only the files the tool names its own in them, and never across a link.
"""
from __future__ import annotations

import json
import os
import pathlib
import re
from typing import Optional, Sequence

from . import point_files
from .command import PROG
from .errors import PointFileError

INDEX = "index.json"
TOOL = PROG  # the tool an output folder's index names
RUN = re.compile(r"run_(\d+)")
INDEX_PARTIAL = re.compile(r"\.index\.json\.partial-\d+")  # an index being written when a run was stopped
# What a run writes inside its folder: tiles, level folders, the levels' work folder of sample ids, the
# input's cells (partition.py), and files being written (point_files' temporary names).
OWN_FILE = re.compile(r"(tile_\d{5,}\.(las|laz|ply|npy)|\.geodesic-lod-[0-9a-f]+\.partial"
                      r"|tile_\d{5,}\.npy\.partial-\d+\.npy"
                      r"|(c\d{7,}_p\d{7,}\.(xyz|ixyz|rows|normals|blocks)|p\d{7,}\.records)\.npy(\.partial-\d+\.npy)?"
                      r"|\.?read_[0-9a-f]{40}\.npy(\.\d+\.\d+)?)")
OWN_FOLDER = re.compile(r"(level_[0-9.]+(pct)?|\.levels|\.cells|reads|\d+)")


class OutputFolder:
    """A folder for a run's output, checked before any work (see the module's docstring)."""

    def __init__(self, path, inputs: Sequence[str]):
        point_files.check_named(path)
        self.path = pathlib.Path(path)
        out = self.path
        if any(point_files.same_file(out, p) for p in inputs):
            raise PointFileError(out, point_files.IS_AN_INPUT)
        if out.is_symlink() and not out.is_dir():
            raise PointFileError(out, "is a link to no folder")
        if out.exists() and not out.is_dir():
            raise PointFileError(out, "exists and is not a folder")
        if out.suffix.lower() in point_files.FORMATS:  # `-o lod.laz` asks for a file, not a folder of tiles
            raise PointFileError(out, f"is named like a point file, but a cluster run writes a folder of tiles and "
                                      f"{INDEX}: name a folder (such as lod/), or a file *{point_files.COPC_SUFFIX} "
                                      "for one COPC file")
        if not out.exists() and not out.parent.is_dir():
            raise PointFileError(out, point_files.no_folder(out.parent))
        where = out if out.exists() else out.parent
        if not os.access(where, os.W_OK | os.X_OK):
            raise PointFileError(out, f"the folder {where} is not writable")
        self.index: Optional[dict] = None
        self.owned: list = []
        if out.exists():
            self._check_contents()
        real = out.resolve()
        for p in inputs:
            if real == pathlib.Path(p).resolve() or real in pathlib.Path(p).resolve().parents:
                raise PointFileError(out, f"holds an input ({p}): choose an output folder apart from the inputs")

    def _check_contents(self):
        entries = {e.name: e for e in os.scandir(self.path)}
        if INDEX in entries:
            try:
                index = json.loads((self.path / INDEX).read_text())
                assert index.get("tool") == TOOL and isinstance(index.get("owned"), list)
                self.index, self.owned = index, [str(n) for n in index["owned"]]
            except (ValueError, AssertionError, OSError, AttributeError):
                raise PointFileError(self.path, f"holds an {INDEX} this tool did not write: choose a new or empty "
                                                "folder") from None
        foreign = sorted(n for n, e in entries.items()
                         if n != INDEX and not (INDEX_PARTIAL.fullmatch(n) and e.is_file(follow_symlinks=False))
                         and (n not in self.owned or e.is_symlink() or not e.is_dir()))
        if foreign:
            shown = ", ".join(foreign[:3]) + (f" and {len(foreign) - 3} more" if len(foreign) > 3 else "")
            raise PointFileError(self.path, f"holds files this tool did not write ({shown}): choose a new or "
                                            "empty folder")

    def begin(self) -> pathlib.Path:
        """A new run folder, recorded as the tool's before anything is written into it."""
        self.created = not self.path.exists()
        self.path.mkdir(exist_ok=True)
        taken = [int(m.group(1)) for n in self.owned if (m := RUN.fullmatch(n))]
        self.run = f"run_{max(taken, default=0) + 1}"
        self.owned.append(self.run)
        self._write_index(dict(self.index or {"tool": TOOL}, owned=self.owned))
        (self.path / self.run).mkdir()
        return self.path / self.run

    def commit(self, index: dict) -> dict:
        """Makes the run the folder's LOD (one rename), then removes the older runs' files."""
        old = [n for n in self.owned if n != self.run]
        self._write_index({"tool": TOOL, **index, "owned": self.owned})
        kept = [n for n in old if not remove_own(self.path / n)]
        self.owned = kept + [self.run]
        index = {"tool": TOOL, **index, "owned": self.owned}
        self._write_index(index)
        return index

    def abort(self) -> None:
        """Removes what the unfinished run wrote (and the index and folder if they were new); what cannot be
        removed stays recorded as the tool's."""
        if not remove_own(self.path / self.run):
            return
        self.owned.remove(self.run)
        if self.index is None and not self.owned:
            (self.path / INDEX).unlink(missing_ok=True)
            if self.created:
                try:
                    self.path.rmdir()
                except OSError:
                    pass
        else:
            self._write_index(dict(self.index or {"tool": TOOL}, owned=self.owned))

    def _write_index(self, index: dict) -> None:
        tmp = self.path / f".{INDEX}.partial-{os.getpid()}"
        tmp.write_text(json.dumps(index, indent=1))
        os.replace(tmp, self.path / INDEX)


def remove_own(folder: pathlib.Path) -> bool:
    """Removes the files and folders a run writes under `folder`, never following a link; whether
    `folder` is gone (it stays if it holds anything else)."""
    if folder.is_symlink() or not folder.is_dir():
        return not folder.exists() and not folder.is_symlink()
    for e in os.scandir(folder):
        if e.is_symlink():
            continue
        if e.is_dir(follow_symlinks=False) and OWN_FOLDER.fullmatch(e.name):
            remove_own(pathlib.Path(e.path))
        elif e.is_file(follow_symlinks=False) and OWN_FILE.fullmatch(e.name):
            os.unlink(e.path)
    try:
        folder.rmdir()
        return True
    except OSError:  # something of someone else's is in it
        return False
