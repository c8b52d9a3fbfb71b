"""The package as a user gets it: a wheel built from this checkout with pip (build isolation, scikit-build-core
and nanobind from PyPI), installed with its pymeshlab extra into a fresh virtual environment, then used there
for arrays, for pymeshlab (no path, no binding loop) and for the command on PLY and LAZ."""
import os
import pathlib
import subprocess
import sys
import textwrap

ROOT = pathlib.Path(__file__).resolve().parents[2]

USE = textwrap.dedent("""
    import sys
    import numpy as np
    import laspy
    import pymeshlab
    import geodesic_lod as gl
    import geodesic_lod.pymeshlab
    assert "site-packages" in gl.__file__, gl.__file__      # the installed package, not the checkout
    rng = np.random.default_rng(3)
    p = rng.normal(size=(3000, 3))
    p /= np.linalg.norm(p, axis=1)[:, None]
    lod = gl.poisson_lod(p, count=200)
    assert len(lod.indices) == 200
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=p))
    res = ms.generate_geodesic_poisson_lod(samplenum=200)
    out = ms.current_mesh().vertex_matrix()
    assert res["sample_num"] == 200 and np.array_equal(out, p[lod.indices])
    # Files for the command: a PLY and a LAZ of the same points.
    ms.set_current_mesh(0)
    ms.save_current_mesh(sys.argv[1] + "/in.ply")
    header = laspy.LasHeader(point_format=6, version="1.4")
    header.scales = [1e-4] * 3
    las = laspy.LasData(header)
    las.x, las.y, las.z = p[:, 0], p[:, 1], p[:, 2]
    las.write(sys.argv[1] + "/in.laz")
    print("ok")
""")


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    assert r.returncode == 0, f"{cmd}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
    return r


def test_wheel_installs_and_works_in_a_fresh_venv(tmp_path):
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    # The wheel's own build folder (build-wheel/) reuses build/'s compiled objects through ccache when
    # the compiler is named alike and paths are taken relative to the checkout.
    build_env = dict(env, CC="cc", CXX="c++", CCACHE_BASEDIR=str(ROOT), CCACHE_NOHASHDIR="true")
    run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-w", str(tmp_path / "dist"), str(ROOT)],
        env=build_env, timeout=1500)
    wheels = list((tmp_path / "dist").glob("geodesic_lod-*.whl"))
    assert len(wheels) == 1, wheels
    import zipfile
    names = zipfile.ZipFile(wheels[0]).namelist()
    assert "geodesic_lod/py.typed" in names and "geodesic_lod/_core.pyi" in names  # typed, with the core's stub
    venv = tmp_path / "venv"
    run([sys.executable, "-m", "venv", str(venv)], env=env)
    py = venv / "bin" / "python"
    run([str(py), "-m", "pip", "install", "-q", f"{wheels[0]}[pymeshlab]"], env=env, timeout=900)
    work = tmp_path / "work"
    work.mkdir()
    assert run([str(py), "-c", USE, str(work)], env=env, cwd=work).stdout.strip() == "ok"
    # The console script, on both files, checked by reading its output back.
    command = venv / "bin" / "geodesic-lod"
    for name in ("in.ply", "in.laz"):
        out = work / name.replace("in.", "lod.")
        run([str(command), str(work / name), "-o", str(out), "--count", "150", "--quiet"], env=env)
        check = f"from geodesic_lod import point_files; print(len(point_files.read({str(out)!r}).points))"
        assert run([str(py), "-c", check], env=env, cwd=work).stdout.strip() == "150"


NUMPY_ONLY = textwrap.dedent("""
    import sys
    import numpy as np
    import geodesic_lod as gl
    p = np.random.default_rng(1).normal(size=(2000, 3))
    assert len(gl.poisson_lod(p, count=100).indices) == 100
    try:
        import geodesic_lod.pymeshlab
    except ImportError as e:
        if sys.argv[1] == "without pymeshlab":
            assert e.name == "pymeshlab", e
        else:
            assert "built without it" in str(e), e
    else:
        raise AssertionError("the plugin is in a numpy-only build")
    print("ok")
""")


def test_the_numpy_only_build_works_from_its_one_option(tmp_path):
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    build_env = dict(env, CC="cc", CXX="c++", CCACHE_BASEDIR=str(ROOT), CCACHE_NOHASHDIR="true")
    run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-w", str(tmp_path / "dist"),
         "-C", "cmake.define.GEODESIC_LOD_BUILD_PLUGIN=OFF", "-C", "build-dir=build-wheel-numpy", str(ROOT)],
        env=build_env, timeout=1500)
    wheels = list((tmp_path / "dist").glob("geodesic_lod-*.whl"))
    assert len(wheels) == 1, wheels
    import zipfile
    assert not any("plugins/" in n and n.endswith(".so") for n in zipfile.ZipFile(wheels[0]).namelist())
    venv = tmp_path / "venv"
    run([sys.executable, "-m", "venv", str(venv)], env=env)
    py = venv / "bin" / "python"
    run([str(py), "-m", "pip", "install", "-q", str(wheels[0])], env=env, timeout=900)
    assert run([str(py), "-c", NUMPY_ONLY, "without pymeshlab"], env=env, cwd=tmp_path).stdout.strip() == "ok"
    # With pymeshlab beside it, importing the plugin's module says the build has none.
    run([str(py), "-m", "pip", "install", "-q", f"{wheels[0]}[pymeshlab]"], env=env, timeout=900)
    assert run([str(py), "-c", NUMPY_ONLY, "with pymeshlab"], env=env, cwd=tmp_path).stdout.strip() == "ok"
