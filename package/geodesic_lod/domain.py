"""Domain: one input's normals, curvature (eq. 1) and geodesic search structure, built once and kept for
several LODs, as a user trying radii or counts does. The functions of geodesic_lod.arrays build it anew on
every call; a Domain's LODs are the same as theirs for the same arguments."""
import functools
from typing import Optional, Sequence, Union

from . import _core
from .docstrings import documented
from .arrays import (DEFAULT_GEODESICS, DEFAULT_LEVELS, DEFAULT_METRIC, DEFAULT_VISIT_ORDER, DOMAIN_DEFAULTS, DomainOptions, FpsLod,
                     LodPyramid, PoissonLod, Progress, call_core, diagonal_of, fps_param, input_arrays,
                     level_counts,
                     poisson_param, pyramid_param, rated, result_of, run_options,
                     placement_of)


@functools.partial(documented, name="Domain")
class Domain:
    def __init__(self, points, normals=None, *, faces=None, metric: str = DEFAULT_METRIC,
                 geodesics: str = DEFAULT_GEODESICS, adaptivity: float = DOMAIN_DEFAULTS.adaptivity,
                 curvature_exponent: float = DOMAIN_DEFAULTS.curvature_exponent,
                 normal_neighbors: int = DOMAIN_DEFAULTS.normal_neighbors, graph_neighbors: int = DOMAIN_DEFAULTS.graph_neighbors,
                 recompute_normals: bool = not DOMAIN_DEFAULTS.use_input_normals, threads: Optional[int] = None,
                 progress: Progress = None):
        p, n, f, has_faces = input_arrays(points, normals, faces)
        options = DomainOptions(metric=metric, geodesics=geodesics, adaptivity=adaptivity,
                                curvature_exponent=curvature_exponent, normal_neighbors=normal_neighbors,
                                graph_neighbors=graph_neighbors, recompute_normals=recompute_normals)
        param = options.param(p.shape[0], has_faces)
        _, threads = run_options(0, threads, progress, False, has_faces)
        self._built = call_core(_core.build_domain, p, n, f, param, threads, progress)
        self._diagonal = diagonal_of(p)

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
                    placement: Optional[str] = None, regions: Optional[str] = None,
                    visit_order: str = DEFAULT_VISIT_ORDER, seed: int = 0, within=None,
                    threads: Optional[int] = None, progress: Progress = None) -> PoissonLod:
        param, threads = poisson_param(self.point_count, self._built.has_faces, radius, count, rate, tolerance,
                                        mesh_output, regions, seed, within, threads, progress,
                                        lambda: self._diagonal, visit_order)
        param.placement = placement_of(placement, mesh_output, param.placement)
        return result_of(PoissonLod, rated(rate, lambda: call_core(_core.poisson_on, self._built, param, threads,
                                                                   progress)))

    @functools.partial(documented, name="Domain.fps_lod")
    def fps_lod(self, *, count: Optional[int] = None, rate: Optional[float] = None, mesh_output: bool = False, placement: Optional[str] = None,
                regions: Optional[str] = None, seed: int = 0, threads: Optional[int] = None,
                progress: Progress = None) -> FpsLod:
        param, threads = fps_param(self.point_count, self._built.has_faces, count, rate, mesh_output, regions,
                                    seed, threads, progress)
        param.placement = placement_of(placement, mesh_output, param.placement)
        return result_of(FpsLod, rated(rate, lambda: call_core(_core.fps_on, self._built, param, threads,
                                                                 progress)))

    @functools.partial(documented, name="Domain.lod_pyramid")
    def lod_pyramid(self, *, levels: Sequence[Union[int, str]] = DEFAULT_LEVELS,
                    mesh_output: bool = False, placement: Optional[str] = None,
                    visit_order: str = DEFAULT_VISIT_ORDER, tolerance: float = 0.0, seed: int = 0,
                    threads: Optional[int] = None, progress: Progress = None) -> LodPyramid:
        param, threads = pyramid_param(level_counts(levels, self.point_count, tolerance), self._built.has_faces,
                                        mesh_output, placement, visit_order, tolerance, seed, threads, progress)
        return result_of(LodPyramid, call_core(_core.pyramid_on, self._built, param, threads, progress))
