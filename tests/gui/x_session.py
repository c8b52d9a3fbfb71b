"""A real X session for GUI tests: Xvfb, screenshots (ImageMagick), text found on
screen by OCR (tesseract), and mouse and keys (xdotool)."""
import csv
import io
import os
import pathlib
import re
import shutil
import subprocess
import time


def _norm(word):
    """A word as compared on screen: letters, digits, '-' and '_' only (case kept: "Apply" is not "apply")."""
    return re.sub(r"[^0-9A-Za-z_\-]", "", word)


class XSession:
    def __init__(self, shots_dir, size="1600x1000"):
        self.shots = pathlib.Path(shots_dir)
        self.shots.mkdir(parents=True, exist_ok=True)
        # Xvfb picks a free display and writes its number to the pipe (a fixed one may be taken).
        read, write = os.pipe()
        self.xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-screen", "0", size + "x24", "-nolisten",
                                      "tcp"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, pass_fds=(write,))
        os.close(write)
        with os.fdopen(read) as pipe:
            number = pipe.readline().strip()
        if not number:
            raise RuntimeError(f"Xvfb did not start (exit code {self.xvfb.wait()})")
        self.display = f":{number}"
        self.env = dict(os.environ, DISPLAY=self.display)
        for _ in range(100):
            if subprocess.run(["xdotool", "getmouselocation"], env=self.env, capture_output=True).returncode == 0:
                break
            time.sleep(0.1)
        else:
            raise RuntimeError(f"Xvfb on {self.display} does not answer")

    def close(self):
        self.xvfb.terminate()
        self.xvfb.wait()

    def run(self, *args, **kw):
        return subprocess.run(list(args), env=self.env, capture_output=True, text=True, **kw)

    def shot(self, name):
        path = self.shots / f"{name}.png"
        self.run("import", "-window", "root", str(path), check=True)
        return path

    def words(self, image, region=None):
        """Words on an image (or its `region`, (x, y, w, h)) with their boxes in screen pixels:
        [(text, left, top, width, height)]. Read at 3x, where tesseract reads small UI fonts reliably."""
        x0, y0 = (region[0], region[1]) if region else (0, 0)
        big = pathlib.Path(str(image) + ".ocr.png")
        cut = ["-crop", "%dx%d+%d+%d" % (region[2], region[3], x0, y0), "+repage"] if region else []
        subprocess.run(["convert", str(image), *cut, "-resize", "300%", "-colorspace", "Gray", str(big)], check=True)
        # One thread: tesseract's OpenMP threads are many times slower on a small machine.
        tsv = subprocess.run(["tesseract", str(big), "-", "--psm", "11", "tsv"], capture_output=True, text=True,
                             check=True, env=dict(os.environ, OMP_THREAD_LIMIT="1")).stdout
        big.unlink()
        out = []
        for row in csv.DictReader(io.StringIO(tsv), delimiter="\t", quoting=csv.QUOTE_NONE):
            if row.get("text", "").strip() and float(row.get("conf", -1)) > 30:
                out.append((row["text"].strip(), x0 + int(row["left"]) // 3, y0 + int(row["top"]) // 3,
                            int(row["width"]) // 3, int(row["height"]) // 3))
        return out

    def find(self, phrase, image=None, name="find", region=None):
        """Centre of the first occurrence of `phrase` (a few words) on the screen or in its
        `region` (x, y, w, h), or None."""
        image = image or self.shot(name)
        ws = [w for w in self.words(image, region) if _norm(w[0])]
        target = [t for t in map(_norm, phrase.split()) if t]
        for i in range(len(ws)):
            seq = ws[i:i + len(target)]
            if len(seq) == len(target) and all(_norm(w[0]) == t for w, t in zip(seq, target)):
                x0, y0 = seq[0][1], min(w[2] for w in seq)
                x1 = seq[-1][1] + seq[-1][3]
                y1 = max(w[2] + w[4] for w in seq)
                return (x0 + x1) // 2, (y0 + y1) // 2
        return None

    def alive(self):
        """Raises if the program under test has ended (a test sets it)."""

    def wait_for(self, phrase, timeout=60, name="wait", region=None):
        end = time.time() + timeout
        while time.time() < end:
            pos = self.find(phrase, name=name, region=region)
            if pos:
                return pos
            self.alive()
            time.sleep(1)
        raise AssertionError(f"'{phrase}' never appeared on screen (last screenshot: {self.shots / name}.png)")

    def click(self, pos):
        self.run("xdotool", "mousemove", str(pos[0]), str(pos[1]), "sleep", "0.3", "click", "1", check=True)
        time.sleep(0.7)

    def hover(self, pos):
        self.run("xdotool", "mousemove", str(pos[0]), str(pos[1]), check=True)
        time.sleep(0.8)

    def key(self, *keys):
        self.run("xdotool", "key", "--delay", "150", *keys, check=True)
        time.sleep(0.7)

    def type(self, text):
        self.run("xdotool", "type", "--delay", "40", text, check=True)
        time.sleep(0.5)


def tools_missing():
    return [t for t in ("Xvfb", "xdotool", "import", "tesseract") if shutil.which(t) is None]
