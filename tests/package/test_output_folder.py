"""geodesic_lod.output_folder on its own: a folder holding anything the tool did not write (a user's file, a
link, a foreign index, an input) is refused, naming it, before anything is written; a run is recorded
before it writes, becomes the LOD in one rename and sweeps the older runs; an interrupted run is
recognised as the tool's; remove_own deletes only the names a run writes and never crosses a link.
(Whole runs on a cluster, failing and rerun: test_distributed_user_files.py.)"""
import json
import os
import pathlib

import pytest

from geodesic_lod import output_folder as of
from geodesic_lod.distributed import level_folder
from geodesic_lod.errors import PointFileError
from test_distributed import files_under
from test_distributed_user_files import snapshot


def own_folder(path, runs=("run_1",)):
    """A folder as the tool leaves it: its index owning `runs`, each a folder holding a tile."""
    path.mkdir()
    for run in runs:
        (path / run).mkdir()
        (path / run / "tile_00000.laz").write_bytes(b"a tile")
    (path / of.INDEX).write_text(json.dumps({"tool": of.TOOL, "owned": list(runs)}))
    return path


def refused(out, inputs=()):
    with pytest.raises(PointFileError) as e:
        of.OutputFolder(out, list(inputs))
    assert e.value.path == out  # the message names the folder
    return e.value.problem


FOREIGN = [("notes.txt", "file"), ("scans", "folder"),
           ("run_1", "link"), ("run_1", "file"),  # where the index has its run folder
           (".index.json.partial-12", "link"), (".index.json.partial-12", "folder"),  # no index being written
           (of.LOCK_FILE, "link"), (of.LOCK_FILE, "folder")]  # no lock of a run


@pytest.mark.parametrize("name, kind", FOREIGN, ids=[f"{k} {n}" for n, k in FOREIGN])
def test_a_folder_holding_anything_the_tool_did_not_write_is_refused_before_any_work(tmp_path, name, kind):
    out = own_folder(tmp_path / "lod")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "data.laz").write_bytes(b"the user's data")
    if name == "run_1":
        (out / "run_1" / "tile_00000.laz").unlink()
        (out / "run_1").rmdir()
    if kind == "link":
        (out / name).symlink_to(elsewhere)
    elif kind == "folder":
        (out / name).mkdir()
    else:
        (out / name).write_text("not the tool's")
    before = snapshot(tmp_path)
    problem = refused(out)
    assert "did not write" in problem and name in problem, problem
    assert snapshot(tmp_path) == before


@pytest.mark.parametrize("text", ['{"tool": "other-tool", "owned": []}', '{"tool": "geodesic-lod"}',
                                  '{"tool": "geodesic-lod", "owned": "run_1"}', '["geodesic-lod"]', "not json",
                                  "\udcff"])
def test_an_index_the_tool_did_not_write_is_refused(tmp_path, text):
    out = tmp_path / "lod"
    out.mkdir()
    (out / of.INDEX).write_bytes(text.encode("utf-8", "surrogateescape"))
    before = snapshot(tmp_path)
    assert f"holds an {of.INDEX} this tool did not write" in refused(out)
    assert snapshot(tmp_path) == before


def test_many_foreign_names_are_shown_three_and_counted(tmp_path):
    out = tmp_path / "lod"
    out.mkdir()
    for name in ("e.txt", "d.txt", "c.txt", "b.txt", "a.txt"):
        (out / name).write_text("x")
    problem = refused(out)
    assert "(a.txt, b.txt, c.txt and 2 more)" in problem, problem


@pytest.mark.parametrize("what, problem", [("a file", "exists and is not a folder"),
                                           ("a link to nothing", "is a link to no folder"),
                                           ("a folder in no folder", "does not exist"),
                                           ("a folder in a file", "notes is a file, not a folder")])
def test_a_path_that_cannot_be_a_folder_is_refused(tmp_path, what, problem):
    out = {"a file": tmp_path / "lod", "a link to nothing": tmp_path / "lod",
           "a folder in no folder": tmp_path / "missing" / "lod",
           "a folder in a file": tmp_path / "notes" / "lod"}[what]
    if what == "a file":
        out.write_text("the user's file")
    elif what == "a folder in a file":
        out.parent.write_text("the user's file")
    elif what == "a link to nothing":
        out.symlink_to(tmp_path / "gone")
    before = snapshot(tmp_path)
    assert problem in refused(out)
    assert snapshot(tmp_path) == before


def test_a_folder_in_one_that_takes_no_new_file_is_refused():
    # /proc takes no new file from anyone, root too, whatever its permissions say.
    out = pathlib.Path("/proc/lod")
    assert refused(out).startswith("the folder /proc takes no new file")
    assert not out.exists()


@pytest.mark.parametrize("through_a_link", [False, True])
def test_an_input_given_as_the_output_folder_is_named_an_input(tmp_path, through_a_link):
    # A careless "-o scan.laz" on a cluster run: say that it is the input, not merely not a folder.
    scan = tmp_path / "scan.laz"
    scan.write_bytes(b"the user's scan")
    given = scan
    if through_a_link:
        given = tmp_path / "link.laz"
        given.symlink_to(scan)
    before = snapshot(tmp_path)
    problem = refused(given, [str(scan)])
    assert "is an input" in problem, problem
    assert snapshot(tmp_path) == before


@pytest.mark.parametrize("through_a_link", [False, True])
def test_a_folder_holding_an_input_is_refused(tmp_path, through_a_link):
    # Sampling a LOD's own tile again into its folder: the commit would remove the input.
    out = own_folder(tmp_path / "lod")
    given = out
    if through_a_link:
        given = tmp_path / "link"
        given.symlink_to(out)
    tile = out / "run_1" / "tile_00000.laz"
    before = snapshot(tmp_path)
    problem = refused(given, [str(tile)])
    assert "holds an input" in problem and str(tile) in problem, problem
    assert snapshot(tmp_path) == before
    of.OutputFolder(given, [str(tmp_path / "elsewhere.laz")])  # the same folder for another input


@pytest.mark.parametrize("state", ["new", "empty", "the tool's", "the tool's, an index write stopped"])
def test_a_new_empty_or_own_folder_is_accepted_and_left_as_it_was(tmp_path, state):
    out = tmp_path / "lod"
    if state == "empty":
        out.mkdir()
    elif state.startswith("the tool's"):
        own_folder(out, runs=("run_1", "run_2"))
    if state.endswith("stopped"):
        (out / ".index.json.partial-4242").write_text('{"tool": "geodesic-')  # killed while writing it
    before = snapshot(tmp_path)
    folder = of.OutputFolder(out, [])
    assert snapshot(tmp_path) == before and out.exists() == (state != "new")
    assert folder.owned == (["run_1", "run_2"] if state.startswith("the tool's") else [])


def test_a_run_is_recorded_before_it_writes_and_numbered_after_the_last(tmp_path):
    out = own_folder(tmp_path / "lod", runs=("run_2", "run_9"))
    run = of.OutputFolder(out, []).begin()
    assert run == out / "run_10" and run.is_dir() and not any(run.iterdir())
    index = json.loads((out / of.INDEX).read_text())
    assert index["tool"] == of.TOOL and index["owned"] == ["run_2", "run_9", "run_10"]
    assert sorted(os.listdir(out)) == [of.INDEX, "run_10", "run_2", "run_9"]  # no index left half-written


def test_an_interrupted_runs_partial_files_are_recognised_and_swept(tmp_path):
    out = tmp_path / "lod"
    folder = of.OutputFolder(out, [])
    run = folder.begin()
    # What a run stopped by SIGKILL leaves: files being written, a level, the levels' work folder.
    (run / ".geodesic-lod-0a1b2c3d4e5f.partial").write_bytes(b"half a tile")
    (run / "level_10pct").mkdir()
    (run / "level_10pct" / "tile_00003.laz").write_bytes(b"a tile")
    (run / "level_10pct" / ".geodesic-lod-99ff.partial").write_bytes(b"half")
    (run / ".levels" / "0").mkdir(parents=True)
    (run / ".levels" / "0" / "tile_00003.npy").write_bytes(b"ids")
    (run / ".levels" / "0" / "tile_00004.npy.partial-311.npy").write_bytes(b"half the ids")
    (out / ".index.json.partial-311").write_text("{")
    folder.close()  # as its process's end does
    again = of.OutputFolder(out, [])  # not refused: all of it is the tool's
    assert again.owned == ["run_1"]
    new = again.begin()
    (new / "tile_00000.laz").write_bytes(b"the new tile")
    index = again.commit({"tiles": [{"file": "run_2/tile_00000.laz"}]})
    assert not run.exists() and index["owned"] == ["run_2"]
    left = [f for f in files_under(out) if f != ".index.json.partial-311"]  # its sweep is not promised
    assert left == sorted([of.INDEX, "run_2/tile_00000.laz"])


def test_a_second_run_into_a_folder_a_run_is_writing_is_refused_until_that_one_ends(tmp_path):
    """Two runs at once into one folder (the command started again in another terminal): the second, checked
    before or after the first began, is refused as it begins and writes nothing; once the first has ended it
    begins, with the folder looked at again, and replaces the first's LOD as any rerun does."""
    out = tmp_path / "lod"
    early = of.OutputFolder(out, [])  # checked before the first run began
    first = of.OutputFolder(out, [])
    run = first.begin()
    (run / "tile_00000.laz").write_bytes(b"the first run's tile")
    before = snapshot(tmp_path)
    for second in (early, of.OutputFolder(out, [])):
        with pytest.raises(PointFileError, match="another run of geodesic-lod is writing it") as e:
            second.begin()
        assert e.value.path == out
    assert snapshot(tmp_path) == before
    first.commit({"tiles": [{"file": "run_1/tile_00000.laz"}]})
    new = early.begin()
    assert new == out / "run_2"
    (new / "tile_00000.laz").write_bytes(b"the second run's tile")
    early.commit({"tiles": [{"file": "run_2/tile_00000.laz"}]})
    assert files_under(out) == sorted([of.INDEX, "run_2/tile_00000.laz"])


@pytest.fixture
def folders_unlockable(monkeypatch):
    """A file system that locks files but no folder, as NFS (a lock needs a file open for writing)."""
    import fcntl
    flock = fcntl.flock

    def no_folder(fd, op):
        if os.path.isdir(f"/proc/self/fd/{fd}"):
            raise OSError(9, "Bad file descriptor")
        return flock(fd, op)
    monkeypatch.setattr(fcntl, "flock", no_folder)


@pytest.mark.parametrize("end", ["commit", "abort"])
def test_where_no_folder_can_be_locked_a_second_run_is_refused_all_the_same(tmp_path, folders_unlockable, end):
    """On a network share the folder's lock is a file of the tool's in it, held as long as the run writes and
    removed as it ends, so the folder is left as a run leaves it anywhere else."""
    out = tmp_path / "lod"
    early = of.OutputFolder(out, [])
    first = of.OutputFolder(out, [])
    run = first.begin()
    assert (out / of.LOCK_FILE).is_file()
    (run / "tile_00000.laz").write_bytes(b"the first run's tile")
    before = snapshot(tmp_path)
    for second in (early, of.OutputFolder(out, [])):  # checked before and after the first began
        with pytest.raises(PointFileError, match="another run of geodesic-lod is writing it"):
            second.begin()
    assert snapshot(tmp_path) == before
    if end == "abort":
        first.abort()
        assert not out.exists()  # new, so removed whole
    else:
        first.commit({"tiles": [{"file": "run_1/tile_00000.laz"}]})
        assert files_under(out) == sorted([of.INDEX, "run_1/tile_00000.laz"])
    new = early.begin()
    (new / "tile_00000.laz").write_bytes(b"the second run's tile")
    early.commit({"tiles": [{"file": f"{new.name}/tile_00000.laz"}]})
    assert files_under(out) == sorted([of.INDEX, f"{new.name}/tile_00000.laz"])


@pytest.mark.parametrize("kind", ["link", "folder"])
def test_a_stranger_at_the_lock_files_name_is_named_as_the_run_begins(tmp_path, folders_unlockable, kind):
    out = own_folder(tmp_path / "lod")
    folder = of.OutputFolder(out, [])
    elsewhere = tmp_path / "elsewhere.txt"
    elsewhere.write_text("the user's")
    (out / of.LOCK_FILE).symlink_to(elsewhere) if kind == "link" else (out / of.LOCK_FILE).mkdir()
    before = snapshot(tmp_path)
    with pytest.raises(PointFileError, match=f"did not write \\({of.LOCK_FILE}\\)"):
        folder.begin()
    assert snapshot(tmp_path) == before


def test_a_lock_file_left_by_a_killed_run_is_the_tools_and_taken(tmp_path, folders_unlockable):
    out = own_folder(tmp_path / "lod")
    (out / of.LOCK_FILE).write_bytes(b"")  # its run was killed: no one holds it
    folder = of.OutputFolder(out, [])
    run = folder.begin()
    with pytest.raises(PointFileError, match="another run"):
        of.OutputFolder(out, []).begin()
    (run / "tile_00000.laz").write_bytes(b"a tile")
    folder.commit({"tiles": [{"file": "run_2/tile_00000.laz"}]})
    assert files_under(out) == sorted([of.INDEX, "run_2/tile_00000.laz"])


def test_a_commit_makes_the_run_the_lod_and_removes_only_the_older_runs_own_files(tmp_path):
    out = own_folder(tmp_path / "lod", runs=("run_1", "run_2"))
    (out / "run_1" / "notes.txt").write_text("the user's, put into the tool's folder")
    folder = of.OutputFolder(out, [])
    run = folder.begin()
    (run / "tile_00000.laz").write_bytes(b"the new tile")
    index = folder.commit({"tiles": [{"file": "run_3/tile_00000.laz"}], "points": 12})
    assert json.loads((out / of.INDEX).read_text()) == index
    assert index["tool"] == of.TOOL and index["points"] == 12
    # run_1 holds the user's file: it stays, recorded as the tool's, so that a later run may sweep it.
    assert index["owned"] == ["run_1", "run_3"]
    assert files_under(out) == sorted([of.INDEX, "run_1/notes.txt", "run_3/tile_00000.laz"])
    assert of.OutputFolder(out, []).owned == ["run_1", "run_3"]


@pytest.mark.parametrize("state", ["new", "empty"])
def test_an_aborted_first_run_leaves_the_folder_as_it_found_it(tmp_path, state):
    out = tmp_path / "lod"
    if state == "empty":
        out.mkdir()
    before = snapshot(tmp_path)
    folder = of.OutputFolder(out, [])
    run = folder.begin()
    (run / "tile_00000.npy").write_bytes(b"a tile")
    (run / ".geodesic-lod-abc.partial").write_bytes(b"half")
    folder.abort()
    assert snapshot(tmp_path) == before and out.exists() == (state == "empty")


def test_an_aborted_rerun_leaves_the_previous_lod_whole(tmp_path):
    out = own_folder(tmp_path / "lod")
    index = json.loads((out / of.INDEX).read_text())
    before = snapshot(tmp_path)
    folder = of.OutputFolder(out, [])
    run = folder.begin()
    (run / "level_50pct").mkdir()
    (run / "level_50pct" / "tile_00000.laz").write_bytes(b"a new tile")
    folder.abort()
    # The index may be written anew (its layout is the tool's), with what it said before.
    assert json.loads((out / of.INDEX).read_text()) == index
    after = snapshot(tmp_path)
    after[str(out / of.INDEX)] = before[str(out / of.INDEX)]
    assert after == before


def test_an_aborted_run_holding_a_strangers_file_stays_recorded_as_the_tools(tmp_path):
    out = own_folder(tmp_path / "lod")
    folder = of.OutputFolder(out, [])
    run = folder.begin()
    (run / "tile_00000.laz").write_bytes(b"a tile")
    (run / "keep.txt").write_text("not the tool's")
    folder.abort()
    assert files_under(out) == sorted([of.INDEX, "run_1/tile_00000.laz", "run_2/keep.txt"])
    assert of.OutputFolder(out, []).owned == ["run_1", "run_2"]


def test_remove_own_removes_only_what_a_run_names_its_own(tmp_path):
    run = tmp_path / "run_1"
    own = ["tile_00000.laz", "tile_00001.las", "tile_00002.ply", "tile_00003.npy", ".geodesic-lod-0f3a.partial",
           "level_2.5pct/tile_00000.laz", "level_300/tile_00000.laz", ".levels/0/tile_00000.npy",
           ".levels/1/tile_00007.npy.partial-88.npy"]
    foreign = ["tile_0001.laz", "tile_00001.txt", "tile_00001.laz.bak", "notes.txt", ".geodesic-lod-xyz.partial",
               "level_x/tile_00000.laz", "level_300/readme", ".levels/x/tile_00000.npy", "scans/tile_00000.laz"]
    for name in own + foreign:
        (run / name).parent.mkdir(parents=True, exist_ok=True)
        (run / name).write_text(name)
    assert of.remove_own(run) is False  # it holds the user's files
    assert files_under(run) == sorted(foreign)
    for name in foreign:
        assert (run / name).read_text() == name
    for name in foreign:
        (run / name).unlink()
    for folder in ("level_x", "level_300", ".levels/x", ".levels", "scans"):
        (run / folder).rmdir()
    (run / "tile_00009.laz").write_text("a tile")
    assert of.remove_own(run) is True and not run.exists()


def test_remove_own_never_follows_a_link_out_of_the_folder(tmp_path):
    outside = tmp_path / "outside"
    (outside / "level_10pct").mkdir(parents=True)
    (outside / "tile_00000.laz").write_bytes(b"the user's data")
    (outside / "level_10pct" / "tile_00001.laz").write_bytes(b"more of it")
    run = tmp_path / "lod" / "run_1"
    (run / ".levels").mkdir(parents=True)
    (run / "tile_00005.laz").write_bytes(b"a tile")
    for name, target in (("level_10pct", outside / "level_10pct"), ("tile_00000.laz", outside / "tile_00000.laz"),
                         (".levels/0", outside), ("level_20pct", outside)):
        (run / name).symlink_to(target)
    before = snapshot(outside)
    of.remove_own(run)
    assert snapshot(outside) == before
    assert not (run / "tile_00005.laz").exists()  # what is the run's own beside the links is removed
    # The run folder itself given as a link: nothing behind it is touched.
    (tmp_path / "lod" / "run_2").symlink_to(outside)
    assert of.remove_own(tmp_path / "lod" / "run_2") is False
    assert snapshot(outside) == before


def test_remove_own_of_a_folder_already_gone_is_done(tmp_path):
    assert of.remove_own(tmp_path / "run_1") is True
    (tmp_path / "run_2").write_text("a file where a run folder was")
    assert of.remove_own(tmp_path / "run_2") is False and (tmp_path / "run_2").exists()


# The names a run writes: level folders (distributed.level_folder of each level the command and lod_files
# accept) and tile files f"tile_{k:05d}{ext}" for each of the tiles (tiles.balanced sets no bound on their number).
@pytest.mark.parametrize("name", [level_folder(item) + "/tile_00000.laz" for item in ("50%", "2.5%", 300, "1e-1%")]
                         + [f"tile_{k:05d}.laz" for k in (0, 99999, 100000)])
def test_every_name_a_run_writes_is_removed_as_its_own(tmp_path, name):
    run = tmp_path / "run_1"
    (run / name).parent.mkdir(parents=True, exist_ok=True)
    (run / name).write_bytes(b"a tile")
    assert of.remove_own(run) is True and not run.exists(), files_under(run)


@pytest.mark.parametrize("name", ["lod.laz", "lod.las", "lod.ply", "lod.npy", "LOD.LAZ"])
def test_a_folder_named_like_a_point_file_is_refused_and_nothing_made(tmp_path, name):
    # `-o lod.laz --workers 2` would make a folder of tiles named lod.laz, not the file the user asked for.
    out = tmp_path / name
    problem = refused(out)
    assert "folder" in problem and "tiles" in problem, problem
    assert not out.exists()


def committed_folder(path):
    """A folder as a complete run leaves it: its index lists run_1's tiles, top level and one level's."""
    path.mkdir()
    (path / "run_1" / "level_10pct").mkdir(parents=True)
    for f in ("run_1/tile_00000.laz", "run_1/level_10pct/tile_00000.laz"):
        (path / f).write_bytes(b"a tile")
    (path / of.INDEX).write_text(json.dumps({
        "tool": of.TOOL, "owned": ["run_1"], "tiles": [{"file": "run_1/tile_00000.laz"}],
        "levels": [{"tiles": [{"file": "run_1/level_10pct/tile_00000.laz"}]}]}))
    return path


@pytest.mark.parametrize("name", ["run_1/tile_00001.las", "run_1/level_10pct/tile_00002.npy",
                                  "run_1/level_50pct/tile_00000.laz", "run_1/notes.txt"])
def test_a_file_in_the_lods_run_that_its_index_does_not_list_is_refused(tmp_path, name):
    """Named like a tile or not, a file the complete run's index does not list is the user's."""
    out = committed_folder(tmp_path / "lod")
    (out / name).parent.mkdir(exist_ok=True)
    (out / name).write_bytes(b"the user's, named like the tool's")
    before = snapshot(tmp_path)
    problem = refused(out)
    assert "did not write" in problem and name in problem, problem
    assert snapshot(tmp_path) == before


def test_a_run_kept_for_a_strangers_file_loses_nothing_to_later_runs(tmp_path):
    """A run folder left because it held someone else's file had its own files removed: whatever appears in
    it later, named like a tile or not, is not the tool's to remove."""
    out = committed_folder(tmp_path / "lod")
    (out / "run_1" / "notes.txt").parent.mkdir(exist_ok=True)
    folder = of.OutputFolder(out, [])
    run = folder.begin()
    (out / "run_1" / "notes.txt").write_text("put there during the run")
    (run / "tile_00000.laz").write_bytes(b"the new tile")
    folder.commit({"tiles": [{"file": "run_2/tile_00000.laz"}]})
    assert files_under(out) == sorted([of.INDEX, "run_1/notes.txt", "run_2/tile_00000.laz"])
    (out / "run_1" / "tile_00007.las").write_bytes(b"the user's, named like a tile")
    folder = of.OutputFolder(out, [])
    run = folder.begin()
    (run / "tile_00000.laz").write_bytes(b"the newest tile")
    folder.commit({"tiles": [{"file": "run_3/tile_00000.laz"}]})
    assert files_under(out) == sorted([of.INDEX, "run_1/notes.txt", "run_1/tile_00007.las", "run_3/tile_00000.laz"])
