"""The COPC viewer (viewer/) in headless Chromium on a COPC file geodesic-lod wrote: the page loads,
draws points, fetches deeper nodes when the camera comes closer, draws what it drew from afar when the
camera goes back, keeps to a point budget and a cache, reads a hierarchy page below the root only when it
refines into its subtree, and logs no error. The screenshots are kept in
out/viewer/ for a person to look at."""
import pathlib
import shutil
import subprocess
import sys

import laspy
import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
VIEWER = ROOT / "viewer"
ARTEFACTS = ROOT / "out" / "viewer"
BACKGROUND = np.array([0x10, 0x14, 0x18]) / 255  # viewer/src/main.js


def needs(ok, what):
    if not ok:
        pytest.skip(f"needs {what} (scripts/setup installs it)")


@pytest.fixture(scope="module")
def copc_file(tmp_path_factory):
    needs(shutil.which("node"), "Node.js")
    needs(pathlib.Path("/usr/bin/chromium").is_file(), "Debian's chromium")
    needs((VIEWER / "dist" / "viewer.js").is_file(), "the built viewer (scripts/build)")
    d = tmp_path_factory.mktemp("viewer")
    # A hilly terrain of 200,000 points over 1 km: an octree of three depths.
    rng = np.random.default_rng(0)
    xy = rng.random((200_000, 2)) * 1000
    z = 40 * np.sin(xy[:, 0] / 150) * np.cos(xy[:, 1] / 200) + 3 * np.sin(xy[:, 0] / 9)
    header = laspy.LasHeader(point_format=6, version="1.4")
    header.scales, header.offsets = [0.01] * 3, [300000.0, 5000000.0, 0.0]
    las = laspy.LasData(header)
    las.x, las.y, las.z = 300000 + xy[:, 0], 5000000 + xy[:, 1], z
    las.write(str(d / "hills.laz"))
    copc = d / "hills.copc.laz"
    r = subprocess.run([sys.executable, "-m", "geodesic_lod", str(d / "hills.laz"), "-o", str(copc), "-q"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return copc


def view(copc, folder, query=""):
    folder.mkdir(parents=True, exist_ok=True)
    sys.path.insert(0, str(VIEWER))
    import serve
    return serve.snapshots(copc, folder, query=query, overwrite=True)  # the folder holds this test's own


@pytest.fixture(scope="module")
def snapshots(copc_file):
    state = view(copc_file, ARTEFACTS)
    with laspy.CopcReader.open(str(copc_file)) as reader:
        depths = max(int(k.level) for k in reader.root_page.entries) + 1
    return state, depths


@pytest.fixture(scope="module")
def budgeted(copc_file, snapshots):
    """The same views with a budget that lets the near view add a third of the points it adds to the far
    view's (room for some of the deeper nodes, not all), and no cache to speak of."""
    far, near = snapshots[0]["far"]["drawnPoints"], snapshots[0]["near"]["drawnPoints"]
    budget = far + (near - far) // 3
    return view(copc_file, ARTEFACTS / "budget", f"budget={budget}&cache=1"), budget


def drawn_fraction(png):
    import matplotlib.image
    rgb = matplotlib.image.imread(str(png))[40:, :, :3]  # below the status line
    return float(np.mean(np.any(np.abs(rgb - BACKGROUND) > 0.05, axis=2)))


def test_the_page_draws_the_coarse_depths_from_afar(snapshots):
    state, depths = snapshots
    assert depths >= 3
    far = state["far"]
    assert far["ready"] and far["drawnPoints"] > 0 and far["maxDepth"] < depths - 1
    assert drawn_fraction(ARTEFACTS / "far.png") > 0.02


def test_coming_closer_loads_deeper_nodes(snapshots):
    state, depths = snapshots
    far, near = state["far"], state["near"]
    assert near["ready"] and near["loadedNodes"] > far["loadedNodes"] and near["maxDepth"] > far["maxDepth"]
    assert near["requests"] > far["requests"]
    assert near["drawnPoints"] > far["drawnPoints"] and drawn_fraction(ARTEFACTS / "near.png") > 0.02


def test_going_back_draws_the_far_view_again_from_what_is_loaded(snapshots):
    state, _ = snapshots
    far, near, back = state["far"], state["near"], state["back"]
    assert back["ready"] and back["drawnPoints"] == far["drawnPoints"] and back["drawnNodes"] == far["drawnNodes"]
    assert back["requests"] == near["requests"] and back["unloadedNodes"] == 0  # within the default cache


def test_a_budget_caps_the_points_drawn_and_the_cache_the_points_kept(snapshots, budgeted):
    state, budget = budgeted
    near, back = state["near"], state["back"]
    assert state["far"]["budget"] == budget and state["far"]["cache"] == 1
    assert near["ready"] and 0 < near["drawnPoints"] <= budget < snapshots[0]["near"]["drawnPoints"]
    # Only what is drawn stays loaded: going back unloads the nodes only the near view drew.
    assert back["ready"] and back["drawnPoints"] == back["loadedPoints"] > 0
    assert near["drawnPoints"] == near["loadedPoints"] and back["unloadedNodes"] > near["unloadedNodes"]
    assert state["errors"] == [] and all(state[k]["errors"] == [] for k in ("far", "near", "back"))


def test_no_error_is_logged(snapshots):
    state, _ = snapshots
    assert state["errors"] == [] and all(state[k]["errors"] == [] for k in ("far", "near", "back"))


@pytest.fixture(scope="module")
def paged(copc_file):
    """The same points written with at most 4 entries a hierarchy page: the root page holds depths 0 and 1
    (5 nodes), and a page below it each subtree of depth 2."""
    out = copc_file.parent / "hills_paged.copc.laz"
    code = ("import sys; import geodesic_lod as gl; from geodesic_lod import copc_files; "
            "copc_files.PAGE_ENTRIES = 4; gl.write_copc(sys.argv[1], sys.argv[2])")
    subprocess.run([sys.executable, "-c", code, str(copc_file.parent / "hills.laz"), str(out)], check=True,
                   timeout=300)
    with laspy.CopcReader.open(str(out)) as reader:
        below = sum(1 for e in reader.root_page.entries.values() if e.point_count == -1)
    return view(out, ARTEFACTS / "paged"), below


def test_a_paged_hierarchy_draws_the_same_reading_pages_as_the_view_reaches_them(snapshots, paged):
    state, below = paged
    assert below > 1
    for k in ("far", "near", "back"):
        got, one = state[k], snapshots[0][k]
        assert got["ready"] and got["errors"] == [], k
        assert (got["drawnNodes"], got["drawnPoints"]) == (one["drawnNodes"], one["drawnPoints"]), k
    # From afar only depths 0 and 1 are drawn (test_the_page_draws_the_coarse_depths_from_afar): the root
    # page is all it reads. Closer, it reads the pages of the subtrees it refines into, not more.
    assert state["far"]["maxDepth"] <= 1 and state["far"]["pages"] == 1
    assert 1 < state["near"]["pages"] <= 1 + below


def test_a_copc_file_the_page_cannot_open_is_one_line_naming_the_pages_error(copc_file, tmp_path):
    """Cut short (a copy stopped midway): the header passes serve.py's check, the page stops on the file."""
    cut = tmp_path / "cut.copc.laz"
    data = copc_file.read_bytes()
    cut.write_bytes(data[: len(data) // 2])
    r = subprocess.run([sys.executable, str(VIEWER / "serve.py"), str(cut), "--snapshots", str(tmp_path)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
    assert r.stderr.startswith(f"serve.py: error: {cut}: the page stopped: ") and "Traceback" not in r.stderr


@pytest.mark.parametrize("n", [1, 50])
def test_a_copc_file_of_points_at_one_position_is_drawn(copc_file, tmp_path, n):
    """No extent to frame (one point, or a clump at one position): the camera still stands off them."""
    header = laspy.LasHeader(point_format=6, version="1.4")
    header.scales, header.offsets = [0.01] * 3, [300000.0, 5000000.0, 0.0]
    las = laspy.LasData(header)
    las.x, las.y, las.z = np.full(n, 300010.0), np.full(n, 5000020.0), np.full(n, 3.0)
    las.write(str(tmp_path / "one.laz"))
    r = subprocess.run([sys.executable, "-m", "geodesic_lod", str(tmp_path / "one.laz"), "-o",
                        str(tmp_path / "one.copc.laz"), "-q"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    state = view(tmp_path / "one.copc.laz", tmp_path / "shots")
    assert not state["errors"]
    for where in ("far", "near"):
        assert state[where]["drawnPoints"] == n, state[where]
