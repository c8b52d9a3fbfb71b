"""The command on one machine never loses a user's file: no output, derived level name or link may be an
input, an existing file is replaced only when asked, everything about the outputs is checked before the
input is read (SIGTERM, like Ctrl-C, leaving no partial file: test_cli.py); a write that fails (a full
disk, a size limit) is one line and leaves nothing."""
import os
import resource
import socket
import subprocess

import laspy
import numpy as np
import pytest

import geodesic_lod as gl
from geodesic_lod import point_files as pf
from point_file_inputs import las_cloud, ply_cloud
from test_cli import COMMAND, digest, run


def contents(folder):
    return {p.name: (os.readlink(p) if p.is_symlink() else digest(p)) for p in folder.iterdir()}


@pytest.mark.parametrize("name, levels", [("lod_50pct.laz", "50%,10%"), ("lod_2000.laz", "2000,400"),
                                          ("lod_10pct.laz", "50%,10%")])
def test_a_level_named_like_an_input_is_refused(tmp_path, name, levels):
    las_cloud(tmp_path / name)
    before = contents(tmp_path)
    r = run(tmp_path / name, "-o", tmp_path / "lod.laz", "--levels", levels, "-q")
    assert r.returncode == 2 and f"{name}: is an input" in r.stderr, r.stderr
    assert contents(tmp_path) == before


def test_an_output_linking_to_the_input_is_refused(tmp_path):
    src = las_cloud(tmp_path / "in.laz")
    (tmp_path / "soft.laz").symlink_to(src)
    os.link(src, tmp_path / "hard.laz")
    before = contents(tmp_path)
    for out in ("soft.laz", "hard.laz"):
        r = run(src, "-o", tmp_path / out, "--rate", "10%", "-q", "--overwrite")
        assert r.returncode == 2 and "is an input" in r.stderr, r.stderr
    assert contents(tmp_path) == before


def test_an_existing_file_is_replaced_only_when_asked(tmp_path):
    src = ply_cloud(tmp_path / "in.ply")
    (tmp_path / "lod.ply").write_text("the user's own file")
    before = contents(tmp_path)
    r = run(src, "-o", tmp_path / "lod.ply", "--rate", "10%", "-q")
    assert r.returncode == 2 and "lod.ply: exists" in r.stderr and "--overwrite" in r.stderr, r.stderr
    assert contents(tmp_path) == before
    assert run(src, "-o", tmp_path / "lod.ply", "--rate", "10%", "-q", "--overwrite").returncode == 0
    assert len(pf.read(tmp_path / "lod.ply").points) == 300


@pytest.mark.parametrize("kind", ["pipe", "socket"])
def test_a_pipe_or_socket_at_the_output_name_is_refused_even_when_replacing_is_allowed(tmp_path, kind):
    """--overwrite allows replacing a file; a pipe or a socket another program reads (or a device node) is
    not one to replace with the LOD."""
    src = ply_cloud(tmp_path / "in.ply")
    out = tmp_path / "lod.ply"
    if kind == "pipe":
        os.mkfifo(out)
    else:
        with socket.socket(socket.AF_UNIX) as bound:  # its file stays once closed
            bound.bind(str(out))
    for replace in ([], ["--overwrite"]):
        r = run(src, "-o", out, "--rate", "10%", "-q", *replace)
        assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
        assert f"{out}: is not a regular file" in r.stderr, r.stderr
        assert sorted(os.listdir(tmp_path)) == ["in.ply", "lod.ply"] and not out.is_file()


@pytest.mark.parametrize("overwrite", [False, True], ids=["not asked", "--overwrite"])
def test_a_file_made_at_the_output_name_during_the_run_is_replaced_only_when_asked(tmp_path, monkeypatch, capsys,
                                                                                   overwrite):
    from geodesic_lod import cli
    src = ply_cloud(tmp_path / "in.ply")
    out = tmp_path / "lod.ply"
    sample = cli._run

    def meanwhile(*args, **kwargs):  # another program, or a second run, writes there as the LOD is made
        out.write_text("the user's own file")
        return sample(*args, **kwargs)
    monkeypatch.setattr(cli, "_run", meanwhile)
    argv = [str(src), "-o", str(out), "--rate", "10%", "-q"] + ["--overwrite"] * overwrite
    if overwrite:
        assert cli.main(argv) == 0
        assert len(pf.read(out).points) == 300
        return
    with pytest.raises(SystemExit) as e:
        cli.main(argv)
    err = capsys.readouterr().err
    assert e.value.code == 2 and err.count("\n") == 1 and f"{out}: appeared while this run worked" in err, err
    assert out.read_text() == "the user's own file" and sorted(os.listdir(tmp_path)) == ["in.ply", "lod.ply"]


def test_an_output_named_twice_is_refused(tmp_path):
    """Level names differ whenever the levels do (the command refuses a level given twice); a list naming
    one file twice, by any spelling, is refused all the same."""
    with pytest.raises(pf.PointFileError, match="would be written twice"):
        pf.check_outputs([], [tmp_path / "lod.ply", tmp_path / "." / "lod.ply"])


@pytest.mark.parametrize("output, problem", [("folder.ply", "is a folder"), ("x" * 300 + ".ply", "name is longer"),
                                             ("lod.ply,lod.ply", "--levels must get strictly coarser")])
def test_output_problems_are_found_before_reading(tmp_path, output, problem):
    (tmp_path / "folder.ply").mkdir()
    # An input that takes minutes to read would show a late check; an unreadable one shows an early one.
    (tmp_path / "in.ply").write_bytes(b"not a PLY file")
    args = ["--levels", "100,100"] if "," in output else ["--rate", "10%"]
    r = run(tmp_path / "in.ply", "-o", tmp_path / output.split(",")[0], *args, "-q")
    assert r.returncode == 2 and problem in r.stderr and "cannot be read" not in r.stderr, r.stderr


def test_a_folder_that_takes_no_new_file_is_found_before_reading(tmp_path):
    # /proc takes no new file from anyone, root too, whatever its permissions say: the output's own
    # name is in the one-line error, not a temporary one.
    (tmp_path / "in.ply").write_bytes(b"not a PLY file")
    r = run(tmp_path / "in.ply", "-o", "/proc/lod.ply", "--rate", "10%", "-q")
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
    assert "/proc/lod.ply: the folder /proc takes no new file" in r.stderr, r.stderr
    assert "partial" not in r.stderr and "cannot be read" not in r.stderr, r.stderr


@pytest.mark.parametrize("output", ["out", "out/", "new/"])
def test_a_folder_as_the_output_of_one_file_is_named_as_such(tmp_path, output):
    (tmp_path / "out").mkdir()
    src = ply_cloud(tmp_path / "in.ply")
    r = run(src, "-o", f"{tmp_path}/{output}", "--rate", "10%", "-q")  # a Path would drop the trailing /
    assert r.returncode == 2 and "is a folder: give the LOD file's name, such as" in r.stderr, r.stderr
    assert "unknown output format" not in r.stderr
    assert not (tmp_path / "new").exists() and not any((tmp_path / "out").iterdir())


def test_a_copc_input_s_suggested_lod_name_is_plain_laz(tmp_path):
    # A LOD of a COPC file is plain LAZ unless named *.copc.laz: the name offered says so.
    src = las_cloud(tmp_path / "scan.laz")
    copc = src.rename(tmp_path / "scan.COPC.laz")
    (tmp_path / "out").mkdir()
    r = run(copc, "-o", tmp_path / "out", "--rate", "10%", "-q")
    assert r.returncode == 2 and f"such as {tmp_path / 'out' / 'scan_lod.laz'}" in r.stderr, r.stderr


def test_a_poisson_lod_keeps_the_inputs_order(tmp_path):
    src = las_cloud(tmp_path / "in.laz")
    assert run(src, "-o", tmp_path / "lod.laz", "--rate", "10%", "-q").returncode == 0
    expected = np.sort(gl.poisson_lod(pf.read(src).points, rate=10).indices)
    records = laspy.read(str(src)).points.array
    assert laspy.read(str(tmp_path / "lod.laz")).points.array.tobytes() == records[expected].tobytes()


def test_version():
    r = run("--version")
    assert r.returncode == 0 and r.stdout.startswith("geodesic-lod ")


def test_a_file_given_twice_is_refused(tmp_path):
    src = las_cloud(tmp_path / "in.laz")
    (tmp_path / "alias.laz").symlink_to(src)
    before = contents(tmp_path)
    for twice in ([src, src], [src, tmp_path / "alias.laz"], [tmp_path, src]):
        r = run(*twice, "-o", tmp_path / "lod", "--rate", "10%", "-q", "--workers", "1")
        assert r.returncode == 2 and "is given twice" in r.stderr and len(r.stderr.splitlines()) == 1, r.stderr
    assert contents(tmp_path) == before


@pytest.mark.parametrize("where", [[], ["--workers", "1"]], ids=["one machine", "cluster"])
def test_an_empty_output_name_is_refused_not_taken_for_the_current_folder(tmp_path, where):
    src = las_cloud(tmp_path / "in.laz")
    before = contents(tmp_path)
    r = run(src, "-o", "", "--rate", "10%", "-q", *where, cwd=tmp_path)
    assert r.returncode == 2 and "the output's name is empty" in r.stderr, r.stderr
    assert contents(tmp_path) == before


@pytest.mark.parametrize("source, output, size", [
    ("in.las", "lod.laz", ["--rate", "50%"]), ("in.las", "lod.las", ["--rate", "50%"]),
    ("in.las", "lod.npy", ["--rate", "50%"]), ("in.las", "lod.ply", ["--rate", "50%"]),
    ("in.ply", "lod.ply", ["--rate", "50%"]),
    ("in.las", "lod.laz", ["--levels", "50%,20%"]), ("in.las", "lod.copc.laz", [])])
def test_a_write_that_fails_is_one_line_and_leaves_nothing(tmp_path, source, output, size):
    # A file size limit fails a write as a full disk does (Python ignores SIGXFSZ: the write raises).
    (las_cloud if source.endswith(".las") else ply_cloud)(tmp_path / source)
    before = contents(tmp_path)
    limit = (tmp_path / source).stat().st_size // 16  # below every LOD, compressed too
    r = subprocess.run(COMMAND + [str(tmp_path / source), "-o", str(tmp_path / output), "-q"] + size,
                       capture_output=True, text=True, timeout=300,
                       preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit)))
    said = [line for line in r.stderr.splitlines() if not line.startswith("geodesic-lod: note: ")]  # a table's
    assert r.returncode == 2 and len(said) == 1, r.stderr
    assert "File too large" in r.stderr and "Traceback" not in r.stderr, r.stderr
    written = output.replace(".laz", "_50pct.laz") if "--levels" in size else output  # the file that failed
    assert f"{tmp_path / written}: File too large" in r.stderr, r.stderr
    assert contents(tmp_path) == before
