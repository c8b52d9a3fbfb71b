"""The output folder of a cluster run, which the tool owns only where it wrote.

``index.json`` is the one record of what the tool wrote there: the LOD (tiles, levels, bounds, CRS),
``owned``, the run folders it made, and ``swept``, those of them left only for someone else's files. A run
refuses a folder holding anything else (files of the user's, links, an input, a file in the LOD's run
folder its index does not list), writes into a new run folder beside the last complete one, and replaces
the index in one rename when complete: an interrupted or failed rerun leaves the previous LOD whole. The
old run folders are removed afterwards, never across a link: of the LOD's run the files its index lists,
of a swept run no file, of a run stopped before it could clean up (killed) the names a run writes. A run
holds the folder's lock from its start to its end: a second run into it at the same time is refused.
"""
from __future__ import annotations

import json
import os
import pathlib
import re
from typing import Optional, Sequence

from . import point_files, stop_signals
from .command import PROG
from .errors import PointFileError

INDEX = "index.json"
TOOL = PROG  # the tool an output folder's index names
RUN = re.compile(r"run_(\d+)")
INDEX_PARTIAL = re.compile(r"\.index\.json\.partial-\d+")  # an index being written when a run was stopped
LOCK_FILE = ".geodesic-lod.lock"  # the folder's lock where the file system locks no folder
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
        point_files.check_creatable(out, where)
        self.index: Optional[dict] = None
        self.owned: list = []
        self.swept: list = []
        self._locked: Optional[int] = None  # the descriptor holding the folder's lock while a run writes
        self._lock_file: Optional[pathlib.Path] = None  # LOCK_FILE, where that descriptor is its
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
                assert isinstance(index.get("swept", []), list)
                self.index, self.owned = index, [str(n) for n in index["owned"]]
                self.swept = [str(n) for n in index.get("swept", [])]
                listed = lod_files(index)
            except (ValueError, AssertionError, OSError, AttributeError, TypeError, KeyError):
                raise PointFileError(self.path, f"holds an {INDEX} this tool did not write: choose a new or empty "
                                                "folder") from None
        foreign = sorted(n for n, e in entries.items()
                         if n != INDEX and not ((INDEX_PARTIAL.fullmatch(n) or n == LOCK_FILE)
                                                and e.is_file(follow_symlinks=False))
                         and (n not in self.owned or e.is_symlink() or not e.is_dir()))
        if INDEX in entries:  # in the LOD's run, what its index does not list is someone else's
            for run in sorted({f.split("/")[0] for f in listed} & set(self.owned) - set(foreign)):
                foreign += [f for f in _files_under(self.path, run) if f not in listed]
        if foreign:
            shown = ", ".join(foreign[:3]) + (f" and {len(foreign) - 3} more" if len(foreign) > 3 else "")
            raise PointFileError(self.path, f"holds files this tool did not write ({shown}): choose a new or "
                                            "empty folder")

    def begin(self) -> pathlib.Path:
        """A new run folder, recorded as the tool's before anything is written into it. The folder is the run's
        alone until commit or abort: a second run into it is refused as it begins, and the folder is looked at
        again once this run has it (it may have changed since it was checked)."""
        self.created = not self.path.exists()
        self.path.mkdir(exist_ok=True)
        self._lock()
        try:
            self.index, self.owned, self.swept = None, [], []
            self._check_contents()
        except BaseException:
            self.close()
            raise
        taken = [int(m.group(1)) for n in self.owned if (m := RUN.fullmatch(n))]
        self.run = f"run_{max(taken, default=0) + 1}"
        self.owned.append(self.run)
        self._write_index(dict(self.index or {"tool": TOOL}, owned=self.owned))
        (self.path / self.run).mkdir()
        return self.path / self.run

    def _lock(self) -> None:
        """An exclusive lock on the folder, held on a descriptor of its own so that it goes with the process
        however it ends. Where the file system locks no folder (NFS locks only files open for writing), the
        lock is on a file of the tool's in it, LOCK_FILE, removed as the run ends; where it locks no file
        either, there is none."""
        import fcntl
        self._locked = os.open(self.path, os.O_RDONLY | os.O_DIRECTORY)
        try:
            fcntl.flock(self._locked, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return
        except BlockingIOError:
            self._refuse()
        except OSError:
            self.close()
        lock_file = self.path / LOCK_FILE
        for _ in range(3):  # again when the run that held it removed it between our open and our lock
            try:
                fd = os.open(lock_file, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o644)
            except OSError:  # a link or a folder of that name: someone else's, which the folder's check names
                return
            try:
                _lock_whole_file(fd)
            except (BlockingIOError, PermissionError):  # held (EAGAIN, or EACCES on some systems)
                os.close(fd)
                self._refuse()
            except OSError:
                os.close(fd)
                return
            try:
                same = os.stat(lock_file, follow_symlinks=False).st_ino == os.fstat(fd).st_ino
            except FileNotFoundError:
                same = False
            if same:
                self._locked, self._lock_file = fd, lock_file
                return
            os.close(fd)
        self._refuse()  # removed every time: other runs are taking it

    def _refuse(self):
        self.close()
        raise PointFileError(self.path, f"another run of {TOOL} is writing it: wait for that run to end, or "
                                        "choose another folder") from None

    def close(self) -> None:
        """Lets another run begin in the folder (commit and abort end with it)."""
        if self._lock_file is not None:
            self._lock_file.unlink(missing_ok=True)  # while still held: a run that opened it looks again
            self._lock_file = None
        if self._locked is not None:
            os.close(self._locked)
            self._locked = None

    def commit(self, index: dict) -> dict:
        """Makes the run the folder's LOD (one rename), then removes the older runs' files."""
        try:
            return self._commit(index)
        finally:
            self.close()

    def _commit(self, index: dict) -> dict:
        old = [n for n in self.owned if n != self.run]
        with stop_signals.held():  # the LOD complete and noted so at once: a stop as the older runs go names it
            self._write_index({"tool": TOOL, **index, **self._ownership()})
            point_files.note_placed([self.path])
        listed = lod_files(self.index or {})
        kept = [n for n in old if not remove_own(self.path / n, self._removable(n, listed))]
        self.owned, self.swept = kept + [self.run], kept
        index = {"tool": TOOL, **index, **self._ownership()}
        self._write_index(index)
        return index

    def _removable(self, run: str, listed: set) -> Optional[set]:
        """The files of an older run that a commit removes, relative to it: those the last LOD (`listed`) lists
        there; none of a run kept for someone else's files (swept); of a run no index listed (an
        interrupted one), every file of the tool's own names (None)."""
        mine = {f[len(run) + 1:] for f in listed if f.startswith(run + "/")}
        return mine if mine or run in self.swept else None

    def abort(self) -> None:
        """Removes what the unfinished run wrote (and the index and folder if they were new); what cannot be
        removed stays recorded as the tool's."""
        try:
            self._abort()
        finally:
            self.close()

    def _abort(self) -> None:
        if not remove_own(self.path / self.run):
            self.swept.append(self.run)
            self._write_index({**(self.index or {"tool": TOOL}), **self._ownership()})
            return
        self.owned.remove(self.run)
        if self.index is None and not self.owned:
            (self.path / INDEX).unlink(missing_ok=True)
            if self.created:
                self.close()  # and its lock file
                try:
                    self.path.rmdir()
                except OSError:
                    pass
        else:
            self._write_index({**(self.index or {"tool": TOOL}), **self._ownership()})

    def _ownership(self) -> dict:
        return {"owned": self.owned, **({"swept": self.swept} if self.swept else {})}

    def _write_index(self, index: dict) -> None:
        tmp = self.path / f".{INDEX}.partial-{os.getpid()}"
        tmp.write_text(json.dumps(index, indent=1))
        os.replace(tmp, self.path / INDEX)


def _lock_whole_file(fd: int) -> None:
    """An exclusive lock on the file open at `fd`, without waiting: an open file description's lock (Linux),
    which other runs in this process cannot take either, else a POSIX one (the process's)."""
    import fcntl
    import struct
    if hasattr(fcntl, "F_OFD_SETLK"):  # struct flock: type, whence, start, length (0: to the end), pid
        fcntl.fcntl(fd, fcntl.F_OFD_SETLK, struct.pack("hhqqi", fcntl.F_WRLCK, os.SEEK_SET, 0, 0, 0))
    else:
        fcntl.lockf(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)


def lod_files(index: dict) -> set:
    """The files an index lists as its LOD's (top level and every level's tiles), relative to its folder."""
    tiles = list(index.get("tiles", [])) + [t for level in index.get("levels", []) for t in level.get("tiles", [])]
    return {str(t["file"]) for t in tiles}


def _files_under(root: pathlib.Path, name: str) -> list:
    """Every entry but a folder under root/name (links as they are, not followed), relative to root."""
    found = []
    for e in os.scandir(root / name):
        if e.is_dir(follow_symlinks=False):
            found += _files_under(root, f"{name}/{e.name}")
        else:
            found.append(f"{name}/{e.name}")
    return found


def remove_own(folder: pathlib.Path, only: Optional[set] = None) -> bool:
    """Removes the files and folders a run writes under `folder` (with `only`, of the files those named
    there, relative to `folder`), never following a link; whether `folder` is gone (it stays if it holds
    anything else)."""
    if folder.is_symlink() or not folder.is_dir():
        return not folder.exists() and not folder.is_symlink()
    for e in os.scandir(folder):
        if e.is_symlink():
            continue
        if e.is_dir(follow_symlinks=False) and OWN_FOLDER.fullmatch(e.name):
            remove_own(pathlib.Path(e.path), None if only is None else
                       {f[len(e.name) + 1:] for f in only if f.startswith(e.name + "/")})
        elif e.is_file(follow_symlinks=False) and (OWN_FILE.fullmatch(e.name) if only is None else e.name in only):
            os.unlink(e.path)
    try:
        folder.rmdir()
        return True
    except OSError:  # something of someone else's is in it
        return False
