"""What the benchmark scripts take from the machine they run on: the binaries the build makes (the
plugin, loaded into pymeshlab here, and the peer tool), the shared models, and this process's memory
as the kernel counts it (Linux /proc), in MB."""
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[1]
PLUGIN = ROOT / "build" / "plugins" / "libfilter_geodesic_lod.so"
PEER_TOOL = ROOT / "build" / "bench-peers" / "peer_simplify"  # CGAL's and Open3D's samplers (bench/peers)
SHARED_DATA = ROOT.parent / "shared" / "data"  # the models, kept beside the checkout


def add_plugin_option(parser):
    """--plugin PATH, defaulting to the build's plugin."""
    parser.add_argument("--plugin", default=str(PLUGIN))


def add_visit_order_option(parser):
    """--visit-order ORDER, the package's orders and default."""
    from geodesic_lod import arrays
    parser.add_argument("--visit-order", default=arrays.DEFAULT_VISIT_ORDER, choices=list(arrays.VISIT_ORDERS))


def load_plugin(path=PLUGIN):
    """pymeshlab with the plugin loaded; imported here so scripts that never load it need no pymeshlab."""
    import pymeshlab
    pymeshlab.load_plugin(str(path))
    return pymeshlab


def _status_mb(field):
    for line in open("/proc/self/status"):
        if line.startswith(field + ":"):
            return int(line.split()[1]) / 1024  # kB; a power of two, so differences stay exact
    return float("nan")


def peak_rss_mb():
    """The process's high-water mark of resident memory (VmHWM)."""
    return _status_mb("VmHWM")


def rss_mb():
    """The process's resident memory now (VmRSS)."""
    return _status_mb("VmRSS")


def reset_peak():
    """Starts peak_rss_mb() again from the memory held now, so a peak belongs to what follows."""
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")
