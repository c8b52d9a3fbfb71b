"""The real MeshLab 2025.07 GUI, built from the same source as the plugin, under Xvfb:
find our filters in the Filters menu (Sampling and Point Set), apply one through its
dialog, export the result and check the file. Screenshots are kept in build/gui-shots;
with GEODESIC_LOD_FIGURES=<dir> the README pictures are written there too."""
import os
import pathlib
import re
import subprocess
import time

import numpy as np
import pymeshlab
import pytest
from scipy.spatial import cKDTree

from x_session import XSession, tools_missing

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("GEODESIC_LOD_BUILD_DIR", ROOT / "build"))
MESHLAB = BUILD / "meshlab" / "src" / "distrib" / "meshlab"
SHOTS = BUILD / "gui-shots"
SHARED = pathlib.Path(os.environ.get("GEODESIC_LOD_SHARED_DATA", ROOT.parent / "shared" / "data"))
# Parts of the maximised 1600x1000 window, where text is looked for (OCR of the whole screen is slow).
VIEWPORT = "1123x868+0+72"  # the 3D view
MENUS = (0, 0, 800, 520)
DIALOG = (480, 40, 800, 960)  # to the window's bottom: Apply and Close; as wide as the dialog grows
LOG = (1130, 770, 470, 160)
LAYERS = (1130, 80, 470, 80)
CENTRE = (300, 150, 1000, 700)


def model(tmp):
    """Stanford's bunny from the shared scans, else a generated bumpy surface."""
    bunny = SHARED / "bunny_35k.ply"
    if bunny.is_file():
        return bunny, "bunny_35k"
    n = 80
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n), indexing="ij")
    z = np.where(x < 0.5, 0.0, 0.05 * (np.sin(8 * np.pi * x) * np.sin(8 * np.pi * y)) ** 2)
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.column_stack([x.ravel(), y.ravel(), z.ravel()]),
                               face_matrix=np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])))
    path = tmp / "bumpy.ply"
    ms.save_current_mesh(str(path), binary=True)
    return path, "bumpy"


@pytest.fixture
def gui(tmp_path):
    missing = tools_missing()
    if missing:
        pytest.skip(f"needs {', '.join(missing)} (scripts/setup installs them)")
    assert MESHLAB.is_file(), f"the MeshLab GUI is not built: {MESHLAB} (scripts/gui-test builds it)"
    session = XSession(SHOTS)
    home = tmp_path / "home"  # a new user: MeshLab asks its first-run question
    home.mkdir()
    env = dict(session.env, HOME=str(home), XDG_CONFIG_HOME=str(home / ".config"))
    inp, name = model(tmp_path)
    log = SHOTS / "meshlab.log"  # MeshLab's own output, which tells why a window never came
    with open(log, "wb") as out:
        proc = subprocess.Popen([str(MESHLAB), str(inp)], env=env, stdout=out, stderr=subprocess.STDOUT)
    session.alive = lambda: _running(proc, log)
    yield session, inp, name
    proc.terminate()
    proc.wait(timeout=20)
    session.close()


def _running(proc, log):
    """Raises, with the end of its output, if MeshLab has exited."""
    if proc.poll() is not None:
        tail = log.read_text(errors="replace")[-2000:]
        raise AssertionError(f"MeshLab exited with code {proc.returncode}; the end of its output ({log}):\n{tail}")


def crop(src, geometry, dst):
    subprocess.run(["convert", str(src), "-crop", geometry, "+repage", str(dst)], check=True)


def test_filters_menu_dialog_apply_and_export(gui, tmp_path):
    s, inp, name = gui
    s.wait_for("statistics", name="01_first_run", timeout=90, region=CENTRE)  # "send usage statistics?": no
    s.key("alt+n")
    s.run("xdotool", "search", "--name", "MeshLab", "windowsize", "%@", "1600", "1000")
    time.sleep(2)
    s.shot("02_input")

    # Both filters under Filters > Point Set and Filters > Sampling, where a user looks.
    for submenu in ("Point Set", "Sampling"):
        s.click(s.wait_for("Filters", name="03_menubar", region=MENUS))
        s.click(s.wait_for(submenu, name="04_filters", region=MENUS))
        shot = s.shot("05_" + submenu.replace(" ", "_"))
        text = " ".join(w[0] for w in s.words(shot, MENUS))
        assert "Geodesic Poisson-disk LOD" in text, f"not in Filters > {submenu}: {text}"
        assert "Geodesic Farthest Point LOD" in text, f"not in Filters > {submenu}: {text}"
        s.key("Escape")
        s.key("Escape")
    # Open the Poisson filter from Filters > Sampling, pick a metric and a radius in its dialog.
    s.click(s.wait_for("Filters", name="06_menubar", region=MENUS))
    s.click(s.wait_for("Sampling", name="07_filters", region=MENUS))
    s.click(s.wait_for("Geodesic Poisson-disk LOD", name="08_sampling", region=MENUS))
    s.click(s.wait_for("Automatic (surface-density", name="09_dialog", region=DIALOG))  # the default
    s.click(s.wait_for("Weighted geodesic (eq. 3)", name="10_metric_list", region=DIALOG))
    perc = s.wait_for("1.000", name="11_dialog", region=DIALOG)
    s.run("xdotool", "mousemove", str(perc[0]), str(perc[1]), "click", "--repeat", "3", "1")
    s.key("ctrl+a")
    s.type("2")
    s.key("Tab")
    dialog = s.shot("12_dialog_set")
    # The dialog's own window, for the README's picture of it (its size follows its contents).
    geo = s.run("xdotool", "search", "--name", "Geodesic Poisson-disk LOD", "getwindowgeometry", "--shell").stdout
    g = dict(line.split("=") for line in geo.split() if "=" in line)
    dialog_crop = f"{g['WIDTH']}x{g['HEIGHT']}+{g['X']}+{g['Y']}" if g else "640x900+480+40"
    # Apply sits below Help, level with Close; tesseract can miss the word on the focused button.
    apply = s.find("Apply", image=dialog, region=DIALOG)
    if apply is None:
        help_, close = s.find("Help", image=dialog, region=DIALOG), s.find("Close", image=dialog, region=DIALOG)
        apply = (help_[0], close[1])
    s.click(apply)
    s.wait_for("samples of", name="13_applied", timeout=120, region=LOG)
    log = " ".join(w[0] for w in s.words(s.shot("13_applied"), LOG))
    # "3,595 samples of": OCR may read the separator as a full stop, or apart from the digits.
    count = int(re.sub(r"\D", "", re.search(r"(\d(?:[\d,. ]*\d)?) samples of", log).group(1)))
    s.click(s.wait_for("Close", name="14_applied", region=DIALOG))
    # Hide the input layer (its eye, left of its row) to see the LOD alone.
    row = s.wait_for(name, name="15_layers", region=LAYERS)
    s.click((row[0] - 75, row[1]))
    s.shot("16_lod")

    # File > Export Mesh As...: name, then the saving options dialog.
    out = tmp_path / "lod.ply"
    s.key("ctrl+e")
    s.wait_for("File name", name="17_export", region=CENTRE)
    s.type(str(out))
    s.key("Return")
    s.wait_for("OK", name="18_save_options", region=CENTRE)
    s.key("Return")
    for _ in range(60):
        if out.is_file() and out.stat().st_size > 0:
            break
        time.sleep(0.5)
    s.shot("19_saved")

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(out))
    lod = ms.current_mesh().vertex_matrix()
    ms.load_new_mesh(str(inp))
    src = ms.current_mesh().vertex_matrix()
    assert len(lod) == count > 0
    dist, idx = cKDTree(src).query(lod)
    assert dist.max() == 0 and len(np.unique(idx)) == len(idx)  # exact input points, each once
    assert len(lod) < len(src)

    # The dialog's choices reached the filter: pymeshlab with that metric and radius (and the other
    # defaults) gives the very same samples, and with the default metric other ones.
    pymeshlab.load_plugin(str(BUILD / "plugins" / "libfilter_geodesic_lod.so"))

    def samples(**params):
        ref = pymeshlab.MeshSet()
        ref.load_new_mesh(str(inp))
        ref.apply_filter("generate_geodesic_poisson_lod", radius=pymeshlab.PercentageValue(2), **params)
        return {tuple(p) for p in ref.current_mesh().vertex_matrix()}

    assert {tuple(p) for p in lod} == samples(metric="Weighted geodesic (eq. 3)")
    assert samples() != samples(metric="Weighted geodesic (eq. 3)"), "the metric choice would go unnoticed"

    figures = os.environ.get("GEODESIC_LOD_FIGURES")
    if figures:
        figs = pathlib.Path(figures)
        figs.mkdir(parents=True, exist_ok=True)
        crop(SHOTS / "05_Sampling.png", "780x520+0+0", figs / "gui_filters_menu.png")
        crop(SHOTS / "12_dialog_set.png", dialog_crop, figs / "gui_parameter_dialog.png")
        crop(SHOTS / "02_input.png", VIEWPORT, tmp_path / "a.png")
        crop(SHOTS / "16_lod.png", VIEWPORT, tmp_path / "b.png")
        subprocess.run(["convert", str(tmp_path / "a.png"), str(tmp_path / "b.png"), "+append",
                        "-resize", "1400x", str(figs / "gui_lod_beside_input.png")], check=True)
