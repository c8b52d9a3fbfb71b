"""Domain: one input's normals, curvature (eq. 1) and geodesic search structure, built once and kept for
several LODs, as a user trying radii or counts does. The functions of geodesic_lod.arrays build it anew on
every call; a Domain's LODs are the same as theirs for the same arguments."""
import functools
from typing import Optional, Sequence, Union

from . import _core
from .docstrings import documented
from .arrays import (DEFAULT_GEODESICS, DEFAULT_LEVELS, DEFAULT_METRIC, FpsLod, LodPyramid, PoissonLod, Progress,
                     _DOMAIN, _common, _diagonal, _domain, _fps_param, _inputs, _lod, _poisson_param,
                     _pyramid_param, _run, level_counts)


@functools.partial(documented, name="Domain")
class Domain:
    def __init__(self, points, normals=None, *, faces=None, metric: str = DEFAULT_METRIC,
                 geodesics: str = DEFAULT_GEODESICS, adaptivity: float = _DOMAIN.adaptivity,
                 curvature_exponent: float = _DOMAIN.curvature_exponent,
                 normal_neighbors: int = _DOMAIN.normal_neighbors, graph_neighbors: int = _DOMAIN.graph_neighbors,
                 recompute_normals: bool = not _DOMAIN.use_input_normals, threads: Optional[int] = None,
                 progress: Progress = None):
        p, n, f, has_faces = _inputs(points, normals, faces)
        param = _domain(p.shape[0], has_faces, metric, geodesics, curvature_exponent, adaptivity,
                        normal_neighbors, graph_neighbors, recompute_normals)
        _, threads = _common(0, threads, progress, False, has_faces)
        self._built = _run(_core.build_domain, p, n, f, param, threads, progress)
        self._diagonal = _diagonal(p)

    @property
    def point_count(self) -> int:
        """The number of input points."""
        return self._built.point_count

    @property
    def nbytes(self) -> int:
        """The memory the domain holds."""
        return self._built.nbytes

    @property
    def mesh_geodesics(self) -> bool:
        """Fast marching over the faces (else the point graph, or Euclidean distances)."""
        return self._built.mesh_geodesics

    @functools.partial(documented, name="Domain.poisson_lod")
    def poisson_lod(self, *, radius: Optional[float] = None, count: Optional[int] = None,
                    rate: Optional[float] = None, tolerance: float = 0.0, mesh_output: bool = False,
                    regions: Optional[str] = None, seed: int = 0, within=None, threads: Optional[int] = None,
                    progress: Progress = None) -> PoissonLod:
        param, threads = _poisson_param(self.point_count, self._built.has_faces, radius, count, rate, tolerance,
                                        mesh_output, regions, seed, within, threads, progress,
                                        lambda: self._diagonal)
        return _lod(PoissonLod, _run(_core.poisson_on, self._built, param, threads, progress))

    @functools.partial(documented, name="Domain.fps_lod")
    def fps_lod(self, *, count: int, mesh_output: bool = False, regions: Optional[str] = None, seed: int = 0,
                threads: Optional[int] = None, progress: Progress = None) -> FpsLod:
        param, threads = _fps_param(self.point_count, self._built.has_faces, count, mesh_output, regions, seed,
                                    threads, progress)
        return _lod(FpsLod, _run(_core.fps_on, self._built, param, threads, progress))

    @functools.partial(documented, name="Domain.lod_pyramid")
    def lod_pyramid(self, *, levels: Sequence[Union[int, str]] = DEFAULT_LEVELS,
                    mesh_output: bool = False, seed: int = 0, threads: Optional[int] = None,
                    progress: Progress = None) -> LodPyramid:
        param, threads = _pyramid_param(level_counts(levels, self.point_count), self._built.has_faces,
                                        mesh_output, seed, threads, progress)
        return _lod(LodPyramid, _run(_core.pyramid_on, self._built, param, threads, progress))
