"""Large synthetic scans with smooth and detailed regions, for the speed benchmarks.

A height field over [0, 1]^2 sampled at uniformly random (x, y), as an aerial or
turntable scan is: gentle hills everywhere; on the half x > 0.5 a displacement of
ridges and bumps at three scales (the detail the LOD should keep); Gaussian noise
along z of a tenth of the mean point spacing. Normals are the exact normals of
the noise-free surface. Generated in chunks so 14M points need little more memory
than the arrays returned.

usage: bench/make_scan.py N OUT.ply [--normals] [--seed S]   (binary PLY, float32)
"""
import argparse

import numpy as np


def _height(x, y):
    """z and its gradient (dz/dx, dz/dy) of the noise-free surface."""
    tau = 2 * np.pi
    z = 0.08 * np.sin(tau * x) * np.cos(tau * y)
    zx = 0.08 * tau * np.cos(tau * x) * np.cos(tau * y)
    zy = -0.08 * tau * np.sin(tau * x) * np.sin(tau * y)
    # Detail only where x > 0.5, faded in over 0.45..0.55 so the surface stays smooth.
    t = np.clip((x - 0.45) / 0.1, 0.0, 1.0)
    fade, dfade = t * t * (3 - 2 * t), np.where((x > 0.45) & (x < 0.55), 60 * t * (1 - t), 0.0)
    d = np.zeros_like(x)
    dx = np.zeros_like(x)
    dy = np.zeros_like(x)
    for amp, freq, angle in ((0.01, 12, 0.3), (0.004, 37, 1.1), (0.0015, 90, 2.0)):
        u = np.cos(angle) * x + np.sin(angle) * y
        v = -np.sin(angle) * x + np.cos(angle) * y
        s, c = np.sin(tau * freq * u), np.cos(tau * freq * v)
        d += amp * s * c
        du = amp * tau * freq * np.cos(tau * freq * u) * c
        dv = -amp * tau * freq * s * np.sin(tau * freq * v)
        dx += du * np.cos(angle) - dv * np.sin(angle)
        dy += du * np.sin(angle) + dv * np.cos(angle)
    return z + fade * d, zx + fade * dx + dfade * d, zy + fade * dy


def make_scan(n, seed=0, normals=False, chunk=1 << 20):
    """(positions float32 n x 3, normals float32 n x 3 or None)."""
    rng = np.random.default_rng(seed)
    pos = np.empty((n, 3), np.float32)
    nrm = np.empty((n, 3), np.float32) if normals else None
    sigma = 0.1 / np.sqrt(n)  # a tenth of the mean spacing
    for a in range(0, n, chunk):
        b = min(n, a + chunk)
        x, y = rng.random(b - a), rng.random(b - a)
        z, zx, zy = _height(x, y)
        pos[a:b, 0], pos[a:b, 1] = x, y
        pos[a:b, 2] = z + rng.normal(0.0, sigma, b - a)
        if normals:
            g = np.column_stack([-zx, -zy, np.ones_like(zx)])
            nrm[a:b] = g / np.linalg.norm(g, axis=1, keepdims=True)
    return pos, nrm


def write_ply(path, pos, nrm=None):
    """Binary little-endian PLY of float32 vertices (x y z [nx ny nz])."""
    props = ["x", "y", "z"] + (["nx", "ny", "nz"] if nrm is not None else [])
    header = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(pos)
    header += "".join("property float %s\n" % p for p in props) + "end_header\n"
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        chunk = 1 << 20
        for a in range(0, len(pos), chunk):
            block = pos[a:a + chunk] if nrm is None else np.hstack([pos[a:a + chunk], nrm[a:a + chunk]])
            f.write(np.ascontiguousarray(block, dtype="<f4").tobytes())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("n", type=int)
    ap.add_argument("out")
    ap.add_argument("--normals", action="store_true")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    pos, nrm = make_scan(args.n, args.seed, args.normals)
    write_ply(args.out, pos, nrm)


if __name__ == "__main__":
    main()
