"""The README's picture of the COPC viewer: a shared airborne file written as COPC by the command, viewed
in headless Chromium (viewer/serve.py --snapshots) from afar and from closer.

usage: PYTHONPATH=build/python .venv/bin/python bench/viewer_screenshot.py
       (writes docs/images/viewer_far.png and docs/images/viewer_near.png)
"""
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from host import ROOT, SHARED_DATA

FILE = SHARED_DATA / "lidar" / "autzen_trim.laz"


def main():
    sys.path.insert(0, str(ROOT / "viewer"))
    import serve
    with tempfile.TemporaryDirectory() as d:
        copc = Path(d) / "autzen_trim.copc.laz"
        subprocess.run([sys.executable, "-m", "geodesic_lod", str(FILE), "-o", str(copc), "-q"], check=True)
        state = serve.snapshots(copc, d)
        for view in ("far", "near"):
            shutil.copy(Path(d) / f"{view}.png", ROOT / "docs" / "images" / f"viewer_{view}.png")
    print(json.dumps(state))


if __name__ == "__main__":
    main()
