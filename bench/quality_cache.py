"""The quality benchmark's cache: one JSON row per model, method and rate, stamped with the key it was
made under. A row is reused, and reported, only under the current key; a stale one is run again and
never reported."""
import hashlib
import json
import pathlib

import quality_config as config

BENCH = pathlib.Path(__file__).resolve().parent
ALL_POINTS = ("all_points", 1.0)  # (method, rate) of the reconstruction from every input point


def file_digest(path):
    path = pathlib.Path(path)
    return hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else "absent"


def run_context(plugin, peer_tool, measure, pymeshlab_version):
    """What changes every run's result besides its model, method and rate: the plugin and the peer tool
    (their binaries), the scripts (the samplers, the methods' parameters), pymeshlab, the measure, the
    reconstruction, and each model file's bytes."""
    return dict(plugin=file_digest(plugin), peer_tool=file_digest(peer_tool),
                script={name: file_digest(BENCH / name) for name in ("quality.py", "quality_config.py")},
                pymeshlab=pymeshlab_version, measure=measure, reconstruction=config.RECONSTRUCTION,
                plane_neighbours=config.PLANE_NEIGHBOURS,
                models={k: file_digest(config.DATA / config.source(k)[0])
                        for k in {**config.MODELS, **config.TUNING_MODELS}})


class RunCache:
    """The rows under `folder` (<model>/<method>_<rate>.json), judged against one run_context."""

    def __init__(self, context, folder=config.RUNS):
        self.context, self.folder = context, pathlib.Path(folder)

    def key(self, model, method, rate):
        blob = json.dumps(dict(context=self.context, model=self.context["models"].get(model), method=method,
                               rate=rate), sort_keys=True)
        return hashlib.sha256(blob.encode()).hexdigest()

    def path(self, model, method, rate):
        name = method if (method, rate) == ALL_POINTS else f"{method}_{rate:g}"
        return self.folder / model.replace(" ", "_") / f"{name}.json"

    def get(self, model, method, rate):
        """The cached row if it was made under the current key, else None (absent or stale)."""
        path = self.path(model, method, rate)
        if not path.is_file():
            return None
        row = json.loads(path.read_text())
        return row if row.get("key") == self.key(model, method, rate) else None

    def current(self):
        """({(model, method, rate): row} of the rows made under the current key, [paths of the stale ones])."""
        runs, stale = {}, []
        for path in self.folder.glob("*/*.json"):
            row = json.loads(path.read_text())
            key = (row["model"], *(ALL_POINTS if path.stem == ALL_POINTS[0] else (row["method"], row["rate"])))
            if row.get("key") != self.key(*key):
                stale.append(path)
                continue
            runs[key] = row
        return runs, stale
