"""viewer/serve.py as a careless user starts it: a file that is not COPC (a plain LAZ, a PLY), a file that is
not there, a port another server holds: one line naming the problem, exit status 2, nothing served."""
import pathlib
import socket
import subprocess
import sys

import laspy
import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SERVE = ROOT / "viewer" / "serve.py"
LIDAR = ROOT.parent / "shared" / "data" / "lidar"


def serve_module():
    sys.path.insert(0, str(SERVE.parent))
    import serve
    return serve


def serve(*args, timeout=20):
    return subprocess.run([sys.executable, str(SERVE), *map(str, args)], capture_output=True, text=True,
                          timeout=timeout)


def one_error_line(r, *words):
    assert r.returncode == 2 and r.stdout == "", (r.returncode, r.stdout, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("serve.py: error: "), r.stderr
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


@pytest.fixture
def plain_laz(tmp_path):
    header = laspy.LasHeader(point_format=6, version="1.4")
    las = laspy.LasData(header)
    xy = np.random.default_rng(0).random((200, 2)) * 10
    las.x, las.y, las.z = xy[:, 0], xy[:, 1], np.sin(xy[:, 0])
    las.write(str(tmp_path / "scan.laz"))
    return tmp_path / "scan.laz"


def test_a_plain_laz_is_refused_with_how_to_make_a_copc_file(plain_laz):
    line = one_error_line(serve(plain_laz, "--port", "0"), str(plain_laz), "not a COPC file")
    assert "geodesic-lod" in line and "scan.copc.laz" in line


def test_a_file_that_is_no_las_at_all_is_refused(tmp_path):
    ply = tmp_path / "scan.ply"
    ply.write_text("ply\nformat ascii 1.0\nelement vertex 0\nend_header\n")
    one_error_line(serve(ply, "--port", "0"), str(ply), "not a LAS or LAZ file")
    empty = tmp_path / "empty.copc.laz"
    empty.write_bytes(b"")
    one_error_line(serve(empty, "--port", "0"), str(empty), "not a LAS or LAZ file")


def test_a_missing_file_or_a_folder_is_refused(tmp_path):
    one_error_line(serve(tmp_path / "gone.copc.laz"), "gone.copc.laz", "no such file")
    one_error_line(serve(tmp_path), str(tmp_path), "is a folder")


@pytest.mark.parametrize("name", ["simple.copc.laz", "lone-star.copc.laz"])
def test_the_shared_copc_files_are_recognised(name):
    """Others' COPC files (PDAL's, untwine's) pass the check: it reads the header and the first record only."""
    if not (LIDAR / name).is_file():
        pytest.skip(f"needs ../shared/data/lidar/{name}")
    assert serve_module().copc_problem(LIDAR / name) is None


def test_a_port_in_use_names_the_port_and_the_option(plain_laz, tmp_path):
    if not (serve_module().DIST / "viewer.js").is_file():
        pytest.skip("needs the built viewer (scripts/build)")
    copc = tmp_path / "scan.copc.laz"
    r = subprocess.run([sys.executable, "-m", "geodesic_lod", str(plain_laz), "-o", str(copc), "-q"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    with socket.socket() as held:
        held.bind(("127.0.0.1", 0))
        held.listen()
        port = held.getsockname()[1]
        one_error_line(serve(copc, "--port", port), f"port {port}", "--port")


@pytest.mark.parametrize("port", ["65536", "99999", "-5"])
def test_a_port_outside_0_to_65535_is_named(plain_laz, port):
    # The socket's own OverflowError was a traceback.
    one_error_line(serve(plain_laz, "--port", port),
                   f"argument --port: {port} is not a port: give one from 0 to 65535 (0: any free port)")


def test_a_bad_option_is_one_line(plain_laz):
    one_error_line(serve(plain_laz, "--port", "abc"), "argument --port: abc is not a port")
    one_error_line(serve(plain_laz, "--zoom", "2"), "unrecognized arguments: --zoom 2")
    one_error_line(serve(plain_laz, "--overwrite"), "--overwrite goes with --snapshots")


def test_screenshots_never_replace_the_users_files(plain_laz, tmp_path):
    """--snapshots DIR writes DIR/far.png and DIR/near.png: a folder holding either is refused unless
    --overwrite, and a file at DIR's name is named; nothing is served."""
    copc = tmp_path / "scan.copc.laz"
    r = subprocess.run([sys.executable, "-m", "geodesic_lod", str(plain_laz), "-o", str(copc), "-q"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    mine = tmp_path / "pictures"
    mine.mkdir()
    (mine / "far.png").write_bytes(b"the user's own picture")
    one_error_line(serve(copc, "--snapshots", mine), str(mine), "far.png", "--overwrite")
    assert (mine / "far.png").read_bytes() == b"the user's own picture"
    one_error_line(serve(copc, "--snapshots", plain_laz), str(plain_laz), "is a file, not a folder")
