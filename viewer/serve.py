"""Serves the COPC viewer (viewer/dist, built by `npm run build`) and one COPC file on 127.0.0.1, with the
HTTP range requests a streaming viewer makes.

usage: python3 viewer/serve.py scan.copc.laz [--port 8000]   (then open the address it prints)
       python3 viewer/serve.py scan.copc.laz --snapshots DIR [--overwrite]  (far.png and near.png from headless
                                                                            Chromium; --overwrite replaces DIR's)
"""
import argparse
import errno
import functools
import http.server
import os
import pathlib
import json
import re
import subprocess
import sys
import threading

DIST = pathlib.Path(__file__).resolve().parent / "dist"
DATA_NAME = "data.copc.laz"  # the name the page asks for by default (viewer/src/main.js)


class Handler(http.server.SimpleHTTPRequestHandler):
    """Static files from DIST, the COPC file as /data.copc.laz, and byte ranges of both."""

    def __init__(self, *args, copc: pathlib.Path, **kwargs):
        self.copc = copc
        super().__init__(*args, directory=str(DIST), **kwargs)

    def translate_path(self, path):
        if path.split("?", 1)[0] == "/" + DATA_NAME:
            return str(self.copc)
        return super().translate_path(path)

    def end_headers(self):
        self.send_header("Accept-Ranges", "bytes")
        self.send_header("Cache-Control", "no-store")
        super().end_headers()

    def send_head(self):
        m = re.fullmatch(r"bytes=(\d+)-(\d*)", self.headers.get("Range", ""))
        path = self.translate_path(self.path)
        if m is None or not os.path.isfile(path):
            return super().send_head()
        size = os.path.getsize(path)
        first = int(m.group(1))
        last = min(int(m.group(2)) if m.group(2) else size - 1, size - 1)
        if first > last:
            self.send_error(416, "range not satisfiable")
            return None
        f = open(path, "rb")
        f.seek(first)
        self.send_response(206)
        self.send_header("Content-Type", self.guess_type(path))
        self.send_header("Content-Range", f"bytes {first}-{last}/{size}")
        self.send_header("Content-Length", str(last - first + 1))
        self.end_headers()
        self.range_left = last - first + 1
        return f

    def copyfile(self, source, outputfile):
        left = getattr(self, "range_left", None)
        if left is None:
            return super().copyfile(source, outputfile)
        while left > 0:
            chunk = source.read(min(left, 1 << 20))
            if not chunk:
                break
            outputfile.write(chunk)
            left -= len(chunk)

    def guess_type(self, path):
        return "application/wasm" if str(path).endswith(".wasm") else super().guess_type(path)

    def log_message(self, *args):  # quiet: a viewer makes hundreds of requests
        pass


def copc_problem(path) -> "str | None":
    """Why `path` is no COPC file, or None: a COPC file is LAS 1.4 whose first record after the header (at byte
    375) is COPC's info (user "copc", record 1), which is all a viewer reads first."""
    with open(path, "rb") as f:
        head = f.read(395)
    if head[:4] != b"LASF":
        return "is not a LAS or LAZ file"
    if len(head) < 395 or head[377:393].rstrip(b"\0") != b"copc" or int.from_bytes(head[393:395], "little") != 1:
        name = pathlib.Path(path).name
        stem = name[:-len(".copc.laz")] if name.endswith(".copc.laz") else pathlib.Path(path).stem
        return (f"is not a COPC file (a LAS/LAZ file without COPC's octree): write one with "
                f"`geodesic-lod {name} -o {stem}.copc.laz`")
    return None


def server(copc, port: int = 0) -> http.server.ThreadingHTTPServer:
    """A server on 127.0.0.1 (port 0: any free one) for the viewer and the COPC file."""
    copc = pathlib.Path(copc).resolve()
    if copc.is_dir():
        raise ValueError(f"{copc}: is a folder: give a COPC file (such as geodesic-lod's scan.copc.laz)")
    if not copc.is_file():
        raise ValueError(f"{copc}: no such file")
    problem = copc_problem(copc)
    if problem:
        raise ValueError(f"{copc}: {problem}")
    if not (DIST / "viewer.js").is_file():
        raise ValueError(f"{DIST} holds no built viewer: run `npm ci && npm run build` in {DIST.parent}")
    try:
        return http.server.ThreadingHTTPServer(("127.0.0.1", port), functools.partial(Handler, copc=copc))
    except OSError as e:
        if e.errno == errno.EADDRINUSE:
            raise ValueError(f"port {port} of 127.0.0.1 is in use (another server?): choose another with --port, "
                             "or 0 for any free one") from None
        raise


SHOTS = ("far.png", "near.png")  # what screenshot.mjs writes into its folder


def snapshots(copc, folder, timeout: float = 300, query: str = "", overwrite: bool = False) -> dict:
    """Serves copc on a free port of 127.0.0.1 while screenshot.mjs views it in headless Chromium (the
    page's URL query `query`, e.g. "budget=100000"), far, near and far again, its screenshots SHOTS in
    `folder`; returns the viewer's state at the three and the errors it logged, and stops the server. A
    folder already holding one of SHOTS is refused unless `overwrite`."""
    folder = pathlib.Path(folder)
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"{folder}: is a file, not a folder for the screenshots")
    held = [name for name in SHOTS if (folder / name).exists()]
    if held and not overwrite:
        raise ValueError(f"{folder}: holds {' and '.join(held)}, which the screenshots would replace: give another "
                         "folder, or --overwrite")
    httpd = server(copc)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    try:
        url = f"http://127.0.0.1:{httpd.server_address[1]}/" + (f"?{query}" if query else "")
        proc = subprocess.run(["node", str(DIST.parent / "screenshot.mjs"), url, str(folder)], capture_output=True,
                              text=True, timeout=timeout, cwd=DIST.parent)
        if proc.returncode != 0:
            raise RuntimeError(f"{copc}: {proc.stderr.strip()}")
        return json.loads(proc.stdout.strip().splitlines()[-1])
    finally:
        httpd.shutdown()
        httpd.server_close()
        thread.join()


def port(text: str) -> int:
    """A TCP port from the command line: 0 to 65535 (0: any free port)."""
    try:
        value = int(text)
    except ValueError:
        value = -1
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"{text} is not a port: give one from 0 to 65535 (0: any free port)")
    return value


class Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, as every other error here, not argparse's usage block
        print(f"serve.py: error: {message} (see serve.py --help)", file=sys.stderr)
        sys.exit(2)


def main(argv=None):
    ap = Parser(description=__doc__.splitlines()[0])
    ap.add_argument("copc", help="a COPC file, such as geodesic-lod's scan.copc.laz")
    ap.add_argument("--port", type=port, default=8000, help="0 to 65535; 0: any free port (default: 8000)")
    ap.add_argument("--snapshots", metavar="DIR", help="screenshots from headless Chromium into DIR, then stop")
    ap.add_argument("--overwrite", action="store_true", help="with --snapshots: replace DIR's far.png and near.png")
    args = ap.parse_args(argv)
    if args.overwrite and not args.snapshots:
        ap.error("--overwrite goes with --snapshots (serving replaces nothing)")
    try:
        if args.snapshots:
            print(json.dumps(snapshots(args.copc, args.snapshots, overwrite=args.overwrite)))
            return 0
        httpd = server(args.copc, args.port)
    except (ValueError, OSError, RuntimeError) as e:
        print(f"serve.py: error: {e}", file=sys.stderr)
        return 2
    print(f"http://127.0.0.1:{httpd.server_address[1]}/ (Ctrl-C stops)", flush=True)
    try:
        httpd.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        httpd.server_close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
