"""The public functions' numpydoc docstrings, with one home for the parameters they share (the inputs,
the metric, the run) and the defaults read from vcg_ext's Param structs. ``documented`` gives a
function its docstring."""
from __future__ import annotations

from . import _core, tile_points, worker_check

_D = _core.DomainParam()
_SCATTERED = _core.SCATTERED_ABOVE  # the automatic choices' threshold (vcg_ext/scatter_share.h)

INPUTS = """points : (n, 3) array of float32 or float64
        The points (the vertices of a mesh). Never modified.
    normals : (n, 3) array of float, optional
        The points' normals; zero or non-finite rows are estimated from the points. Default: none, all
        estimated."""

FACES = """faces : (m, 3) array of int, optional
        Triangles over the points: geodesics then run over them (fast marching). Default: none."""

METRIC = f"""metric : {{'automatic', 'curvature-density', 'eq3', 'geodesic', 'euclidean', 'surface-density'}}
        The distance the samples are spread in: ``'curvature-density'``, (1 + a (v_i + v_j) / 2) |p_i - p_j|;
        ``'eq3'``, the method's exp(|v_i - v_j|^c) |p_i - p_j|; ``'geodesic'``, unweighted;
        ``'euclidean'``, straight lines; ``'surface-density'``, (1 + (s_i + s_j) / 2) |p_i - p_j| with s_i
        = a / 3 times a point's flatness (1 on a plane, 0 in an even scatter such as leaves), up to twice
        that at a surface's rim: for airborne LiDAR, where it gives ground and roofs the samples the
        curvature-density metric spends on vegetation (best with ``visit_order='rims'``).
        ``'automatic'`` (the default): ``'surface-density'`` where more than {_SCATTERED:.0%} of the points'
        neighbourhoods scatter (airborne LiDAR), else ``'curvature-density'``; the result's ``metric``
        names the one taken.
    geodesics : {{'auto', 'mesh', 'point-graph'}}
        Where geodesics run: ``'mesh'`` over the faces, ``'point-graph'`` on the symmetric k-nearest-neighbour
        graph; ``'auto'`` (the default) picks the mesh where there are faces.
    adaptivity : float
        a of the curvature- and surface-density metrics, >= 0: how much denser rugged parts (smooth
        surfaces) get. Default {_D.adaptivity:g}.
    curvature_exponent : float
        c of eq. 3, > 0. Default {_D.curvature_exponent:g}.
    normal_neighbors : int
        k of the normals' plane fits and of eq. 1, below the number of points. Default {_D.normal_neighbors}.
    graph_neighbors : int
        k of the point graph, below the number of points. Default {_D.graph_neighbors}.
    recompute_normals : bool
        Estimate every normal, ignoring ``normals``. Default {not _D.use_input_normals}."""

RUN = """seed : int
        Seed of the visiting order (with a key order, of the points whose keys tie) and of the first farthest
        point, 0 to 2**64 - 1. Default 0.
    threads : int, optional
        Threads to use (default: all cores). The result is the same on any number.
    progress : callable, optional
        Called with the fraction done, 0 to 1. Ctrl-C stops a run with KeyboardInterrupt."""

MESH_OUTPUT = """mesh_output : bool
        Triangulate the samples over the faces (geodesic Delaunay), in ``faces`` of the result; needs
        ``faces``. Default False."""

# The placements by the names placement= takes (here, where they are explained).
PLACEMENTS = {"optimized": _core.Placement.Optimized, "fitted": _core.Placement.Quadric,
              "input": _core.Placement.InputVertices}
DEFAULT_PLACEMENT = next(k for k, v in PLACEMENTS.items() if v == _core.PoissonParam().placement)

PLACEMENT = f"""placement : {{'optimized', 'fitted', 'input'}}, optional
        With ``mesh_output``: where the mesh's vertices go, in ``positions`` of the result (a pyramid's
        levels: ``level_positions``, each placed for its own level). 'fitted': each moved to the point
        nearest (in least squares) to the planes of the input's triangles in its geodesic Voronoi region,
        never across a border. 'optimized': so fitted, then the mesh optimized to the input's points,
        edges flipped (changing ``faces``) and vertices moved by least squares where that brings the
        triangles nearer to the points. 'input': the input's points. Default (None):
        ``'{DEFAULT_PLACEMENT}'`` with ``mesh_output``; without it the
        positions are the input's."""

RAISES = """Raises
    ------
    InputError
        A bad argument (a ValueError naming it), before any work."""

POISSON_SIZE = """radius : float or str, optional
        The disk radius in the metric, or a string such as ``'1%'``: a percentage of the bounding box
        diagonal.
    count : int, optional
        Exactly this many samples (1 to the points that may be samples): the radius is searched and a
        slightly denser Poisson set thinned, the samples nearest to others first.
    rate : float or str, optional
        A percentage of the points as a count: 10 or ``'10%'`` (0.1 is a thousandth, with a warning that a
        tenth is 10; ``'0.1%'`` says it is meant).
    tolerance : float
        With ``count`` or ``rate``: a Poisson set within this percentage of the count is kept untrimmed.
        Default 0 (an exact count)."""

FPS_SIZE = """count : int, optional
        The number of samples, 1 to the number of points.
    rate : float or str, optional
        A percentage of the points as a count, as in ``poisson_lod``. Give exactly one of ``count`` and
        ``rate``."""

POISSON_EXAMPLE = """Examples
    --------
    >>> import numpy as np, geodesic_lod as gl
    >>> p = np.random.default_rng(0).normal(size=(2000, 3))
    >>> p /= np.linalg.norm(p, axis=1)[:, None]
    >>> lod = gl.poisson_lod(p, count=100)
    >>> len(lod.indices), lod.radius > 0
    (100, True)"""

# The attributes every sampler's result has (k: the samples, n: the input's rows).
LOD_SAMPLES = """indices : (k,) ndarray of int64
        Rows of the input chosen, in sampling order.
    normals : (k, 3) ndarray of float64
        n_i of each sample, of unit length: the input's, or estimated.
    curvature : (k,) ndarray of float64
        v_i (eq. 1) of each sample: the normal variation around it, no unit, 0 on a plane, at most 1."""

LOD_MESH = """faces : (f, 3) ndarray of int64
        With ``mesh_output``: the triangles over the samples, as rows of ``indices`` (0 to k - 1); else (0, 3).
    positions : (k, 3) ndarray of float64
        Each sample's position, in the input's units: its input point, or fitted (``placement``)."""

LOD_REGIONS = """region_of : (n,) ndarray of int64
        With ``regions``: per input row, the rank in ``indices`` of the sample whose region holds it (-1:
        none); else empty."""

LOD_DOMAIN = f"""point_count : int
        Points sampled from.
    estimated_normals : int
        Normals estimated from the points (the others are the input's).
    components : int
        Connected parts of the geodesic domain (0 in the Euclidean metric).
    left_out : int
        Input rows in no triangle: mesh geodesics do not sample them.
    repeated : int
        Input rows of a cloud at the position of an earlier row, or within a millionth of the cloud's size of
        it: one point with it, never a sample, its region theirs.
    mesh_geodesics : bool
        Whether geodesics ran over the faces (fast marching), else on the point graph or in straight lines.
    metric : str
        The metric the samples are spread in: the one asked for, or the automatic choice.
    scatter_share : float
        The share of the points whose neighbourhoods scatter, measured on a subsample chosen by their rows;
        above {_SCATTERED:g} the automatic choices take the surface-density metric and the rims first."""

# An Attributes section opening with the attributes of every sampler's result.
LOD_ATTRIBUTES = f"""Attributes
    ----------
    {LOD_SAMPLES}
    {LOD_MESH}
    {LOD_REGIONS}
    {LOD_DOMAIN}"""

VISIT_ORDER = f"""visit_order : {{'automatic', 'random', 'prominence', 'rims'}}
        Which point of a neighbourhood a disk keeps; every order keeps the separation and the coverage.
        'prominence': the points that stand out of their scan's scatter at the disks' scale first, on a scan's
        scattered points those off the surface their neighbours fit later (docs/visit_order.json). 'random': the paper's seeded order. 'rims': the points at the rim of their
        surroundings first, such as a roof's edges (docs/airborne_classes.md). 'automatic' (the default):
        'rims' where the points scatter (as the automatic metric chooses), else 'prominence'. The same on
        a cluster (``lod_files``, ``copc_file``)."""

PYRAMID_TOLERANCE = """tolerance : float
        At every level, a Poisson set within this percentage of the level's count is kept untrimmed (faster
        on large clouds; the command's ``--levels`` with ``--tolerance``); levels too close for it are
        refused (``level_counts``). Default 0 (exact counts)."""

TEXTS = {
    "poisson_lod": f"""Geodesic Poisson-disk LOD: samples pairwise farther apart than a radius in the metric, every
    point within it of a sample.

    Parameters
    ----------
    {INPUTS}
    {POISSON_SIZE}
        Give exactly one of ``radius``, ``count`` and ``rate``.
    {FACES}
    {METRIC}
    {MESH_OUTPUT}
    {PLACEMENT}
    regions : {{None, 'disk', 'voronoi'}}
        Fill ``region_of`` with each point's sample: its disk's or its nearest. Default None.
    {VISIT_ORDER}
    within : array of int or bool, optional
        The only points that may become samples (indices or a mask), such as a finer level's; the
        geodesics still run over every point.
    {RUN}

    Returns
    -------
    PoissonLod
        ``indices`` (in visiting order), ``radius``, ``covering_radius``, ``normals``, ``curvature``, ...

    {RAISES}

    {POISSON_EXAMPLE}
    """,
    "fps_lod": f"""Geodesic farthest-point LOD: each sample the point farthest from those before it, so
    ``indices[:k]`` is the k-sample LOD.

    Parameters
    ----------
    {INPUTS}
    {FPS_SIZE}
    {FACES}
    {METRIC}
    {MESH_OUTPUT}
    {PLACEMENT}
    regions : {{None, 'voronoi'}}
        Fill ``region_of`` with each point's nearest sample. Default None.
    {RUN}

    Returns
    -------
    FpsLod
        ``indices`` in farthest-point order; ``covering_radii[k]``, the covering radius of the first k + 1.

    {RAISES}

    Examples
    --------
    >>> import numpy as np, geodesic_lod as gl
    >>> p = np.random.default_rng(0).normal(size=(2000, 3))
    >>> fps = gl.fps_lod(p, count=50)
    >>> bool(np.all(np.diff(fps.covering_radii) <= 0))
    True
    """,
    "lod_pyramid": f"""Nested LODs in one run: the finest level a Poisson-disk set of its count, every coarser
    level the Poisson-disk set of its count among the finer level's samples, each in the visiting order at
    its own scale (the command's ``--levels``).

    Parameters
    ----------
    {INPUTS}
    levels : sequence of int or str, or str
        The levels' counts, finest first, strictly decreasing: counts (5000) or percentages of the points
        (``'10%'``), as a list, a comma-separated string or a 1-D integer array of counts. Default
        ``{_core.DEFAULT_LEVELS!r}``.
    {FACES}
    {METRIC}
    {MESH_OUTPUT}
    {PLACEMENT}
    {VISIT_ORDER}
    {PYRAMID_TOLERANCE}
    {RUN}

    Returns
    -------
    LodPyramid
        ``levels``: the index arrays, finest first, each a prefix of the finer ones.

    {RAISES}

    Examples
    --------
    >>> import numpy as np, geodesic_lod as gl
    >>> p = np.random.default_rng(0).normal(size=(2000, 3))
    >>> [len(level) for level in gl.lod_pyramid(p, levels="10%,50").levels]
    [200, 50]
    """,
    "normal_variation": f"""Curvature as normal variation (eq. 1) of every point, with the normals it used.

    Parameters
    ----------
    {INPUTS}
    normal_neighbors : int
        k of the normals' plane fits and of eq. 1. Default {_D.normal_neighbors}.
    recompute_normals : bool
        Estimate every normal, ignoring ``normals``. Default {not _D.use_input_normals}.
    threads, progress
        As in ``poisson_lod``.

    Returns
    -------
    NormalVariation
        ``curvature`` and ``normals`` per point, in the input's order.

    {RAISES}

    Examples
    --------
    >>> import numpy as np, geodesic_lod as gl
    >>> x, y = np.meshgrid(np.linspace(0, 1, 30), np.linspace(0, 1, 30))
    >>> flat = np.column_stack([x.ravel(), y.ravel(), np.zeros(900)])
    >>> float(gl.normal_variation(flat).curvature.max()) < 1e-6
    True
    """,
    "scatter_share": f"""The share of the points whose 20 nearest scatter rather than lie along a plane, which the
    automatic metric and visiting order follow: above {_SCATTERED:g}, the surface-density metric with the
    rims first (airborne LiDAR), else the curvature-density metric with the prominent points first. Measured,
    as every sampler measures it, on at most 65,536 of the points (every point up to that size, else evenly
    through their rows), so that it is the same on one machine and on a cluster.

    Parameters
    ----------
    points : (n, 3) array of float32 or float64
        The points. Never modified.

    Returns
    -------
    float
        From 0 (every neighbourhood on a surface) to 1; a result's ``scatter_share`` is this.

    {RAISES}

    Examples
    --------
    >>> import numpy as np, geodesic_lod as gl
    >>> leaves = np.random.default_rng(0).random((5000, 3))
    >>> gl.scatter_share(leaves) > 0.5
    True
    """,
    "Domain.poisson_lod": f"""``poisson_lod`` on this domain: the same samples as the function gives for the
    domain's inputs and these arguments.

    Parameters
    ----------
    {POISSON_SIZE}
    {MESH_OUTPUT}
    {PLACEMENT}
    regions, visit_order, within
        As in ``poisson_lod``.
    {RUN}

    {RAISES}

    Examples
    --------
    >>> import numpy as np, geodesic_lod as gl
    >>> p = np.random.default_rng(0).normal(size=(2000, 3))
    >>> dom = gl.Domain(p)
    >>> [len(dom.poisson_lod(rate=r).indices) for r in (10, 5)]
    [200, 100]
    """,
    "Domain.fps_lod": f"""``fps_lod`` on this domain.

    Parameters
    ----------
    {FPS_SIZE}
    {MESH_OUTPUT}
    {PLACEMENT}
    regions : {{None, 'voronoi'}}
        As in ``fps_lod``.
    {RUN}

    {RAISES}
    """,
    "Domain.lod_pyramid": f"""``lod_pyramid`` on this domain.

    Parameters
    ----------
    levels : sequence of int or str, or str
        As in ``lod_pyramid``. Default ``{_core.DEFAULT_LEVELS!r}``.
    {MESH_OUTPUT}
    {PLACEMENT}
    {VISIT_ORDER}
    {PYRAMID_TOLERANCE}
    {RUN}

    {RAISES}
    """,
    "lod_files": f"""Samples point files as one cloud on a Dask cluster and writes the LOD as tiles with an
    ``index.json``: exactly ``poisson_lod`` on all the files' points together (ids in file order), for any
    tiling and number of workers.

    Parameters
    ----------
    inputs : sequence of str
        Point files (.las, .laz, .ply, .npy of one format), folders of them, or globs.
    out_dir : str or path
        The output folder: new, empty, or one this function wrote before (its ``index.json`` lists what
        it owns); anything else in it is refused. Each run writes a new ``run_N/`` and replaces the index
        when complete.
    radius : float or str, optional
        As in ``poisson_lod`` (a percentage of the whole cloud's diagonal).
    count, rate : optional
        As in ``poisson_lod``: the same count search, each run over all tiles, from the same first
        radius; no exact count (see ``tolerance``).
    levels : sequence of int or str, or str, optional
        Nested levels, finest first: each the Poisson set of its count among the finer level's samples,
        written into ``run_N/level_.../``. Give exactly one of ``radius``, ``count``, ``rate`` and
        ``levels``.
    tolerance : float
        The percentage a count may miss by, above 0 and below 100; levels too close for it are refused
        (``level_counts``). Default 1.
    max_runs : int, optional
        Poisson runs of a count search at most. Default: one machine's, {_core.PoissonParam().max_iterations}.
    seed : int
        As in ``poisson_lod``. Default 0.
    metric : str
        As in ``poisson_lod`` (the point graph's geodesics). Default ``{_core.Metric(_D.metric).name}``.
    adaptivity : float
        As in ``poisson_lod``. Default {_D.adaptivity:g}.
    tile_points : int
        Points per tile, at most (but where one block of the cells holds more), at least
        {tile_points.MINIMUM}. Default {tile_points.DEFAULT:,}.
    client : dask.distributed.Client
        The cluster (see ``local_cluster``). A cluster with no worker yet is waited for, as Dask waits:
        workers may join later; where the last was lost unexpectedly (a nanny stops a worker past its
        memory limit) and none joins within {worker_check.LOST_WORKER_WAIT:g} s, or one is lost meanwhile, a
        ClusterJobError. So too where the last worker is lost during the job and none joins within
        {worker_check.LOST_WORKER_WAIT:g} s (a nanny may fail to start its worker again), where every worker
        stays paused for {worker_check.PAUSED_WAIT:g} s (its memory past Dask's pause threshold), or where the job's
        results are lost with their worker more often than Dask's ``distributed.scheduler.allowed-failures``
        lets a task be (a nanny stops a worker past its limit between tasks too).
    threads : int, optional
        Threads per task (default: all the worker machine's cores).
    progress : callable, optional
        Called with (tasks done, tasks so far).
    visit_order : {{'automatic', 'random', 'prominence', 'rims'}}
        As in ``poisson_lod``, and the same default.

    Returns
    -------
    dict
        The index: tiles (paths relative to it), counts, bounds, radius, point format, CRS, parameters
        (``metric`` and ``visit_order`` as taken, the automatic choices made for the whole cloud from its
        ``scatter_share``).

    Raises
    ------
    InputError
        A bad argument, input file or output folder (PointFileError names the file).
    ClusterJobError
        Workers too small for their tiles, or lost with none to take their place.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib, geodesic_lod as gl
    >>> from dask.distributed import Client
    >>> from geodesic_lod.distributed import local_cluster, lod_files
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> p = np.random.default_rng(0).normal(size=(5000, 3))
    >>> np.save(d / "cloud.npy", p / np.linalg.norm(p, axis=1)[:, None])
    >>> with local_cluster(1) as cluster, Client(cluster) as client:
    ...     index = lod_files([str(d / "cloud.npy")], d / "lod", radius=0.1, client=client, tile_points=2000)
    >>> index["samples"] == len(gl.poisson_lod(np.load(d / "cloud.npy"), radius=0.1).indices)
    True
    """,
    "height_field_lod": f"""Height-field LOD (terrain, a DEM's nodes, an airborne cloud): greedy insertion, each new
    sample the point farthest in height from the Delaunay TIN of the samples before it (Garland and
    Heckbert's error-driven insertion), among the points at least ``separation * sqrt(A / k)`` from every
    sample (A: the area of the points' convex hull in x, y; k: the samples so far). The samples
    start with the hull's corners and are nested: every prefix from ``hull_size`` on is the LOD of its
    count, with its TIN from ``tin(k)``.

    Parameters
    ----------
    points : (n, 3) array of float32 or float64
        The points, z up; rows with the same x, y give at most one sample. Never modified. A raster of
        heights (rows by columns) is given as its nodes' rows x, y, z, as in the example.
    count : int, optional
        Exactly this many samples: at least the hull's corners, at most the distinct points in x, y.
    rate : float or str, optional
        A percentage of the points as a count: 10 or ``'10%'`` (below 1 without ``%``, with a warning, as in
        ``poisson_lod``). Give exactly one of ``count`` and ``rate``.
    separation : float
        beta, >= 0: the disks' size relative to an even spread of k samples over the hull; 0 is plain
        greedy insertion. Default {_core.HeightFieldParam().separation:g}.
    separation_in : {{'xyz', 'xy'}}
        Where the disks' distance is measured: in x, y, z, so that a cliff's top and foot may both be
        samples (the default), or in x, y.
    progress : callable, optional
        Called with the fraction done, 0 to 1. Ctrl-C stops a run with KeyboardInterrupt.

    Returns
    -------
    HeightFieldLod
        ``indices`` (the hull's corners, then in insertion order), ``errors``, ``faces`` (the TIN of
        all samples), ``hull_size``, ``separated_prefix``, ``tin(k)``.

    {RAISES}

    Examples
    --------
    >>> import numpy as np, geodesic_lod as gl
    >>> y, x = np.mgrid[0:50, 0:50] * 30.0
    >>> dem = np.column_stack([x.ravel(), y.ravel(), (100 * np.sin(x / 300) * np.cos(y / 400)).ravel()])
    >>> lod = gl.height_field_lod(dem, rate=5)
    >>> len(lod.indices), lod.hull_size, int(lod.tin(10).max())  # the TIN of the first 10 samples
    (125, 4, 9)
    """,
    "level_counts": f"""Sample counts of pyramid levels, finest first, as ``lod_pyramid`` and the command's
    ``--levels`` read them.

    Parameters
    ----------
    levels : sequence of int and str, or str
        The levels, finest first: counts (5000) or percentages of the points (``'50%'``, above 0 to 100),
        each giving strictly fewer samples than the one before; or a comma-separated string of them
        (``'50%,10%,500'``), or a 1-D integer array of counts. The pyramid filter's default is
        ``{_core.DEFAULT_LEVELS}``.
    n : int
        The number of points the percentages are of.
    tolerance : float
        The count tolerance (a percentage, as ``poisson_lod``'s and ``lod_files``' take it) the levels are
        searched with: each level's most accepted count must stay below the fewest its finer level accepts.
        Default 0 (exact counts).

    Returns
    -------
    list of int
        The counts, finest first; a percentage rounds as the MeshLab filters round it.

    {RAISES}

    Examples
    --------
    >>> import geodesic_lod as gl
    >>> gl.level_counts("50%,10%,300", 10000)
    [5000, 1000, 300]
    """,
    "HeightFieldLod.tin": """The TIN of the first ``k`` samples: a Delaunay triangulation in x, y.

    Parameters
    ----------
    k : int
        The samples, from ``hull_size`` (the hull's corners) to ``len(indices)``.

    Returns
    -------
    (f, 3) array of int64
        Triangles as rows of ``indices[:k]``, counter-clockwise seen from +z.

    Raises
    ------
    InputError
        (a ``ValueError``) when ``k`` is not a whole number in that range.

    Examples
    --------
    >>> import numpy as np, geodesic_lod as gl
    >>> y, x = np.mgrid[0:20, 0:20] * 30.0
    >>> lod = gl.height_field_lod(np.column_stack([x.ravel(), y.ravel(), np.hypot(x, y).ravel()]), count=40)
    >>> tin = lod.tin(10)
    >>> tin.shape[1], int(tin.max()) < 10
    (3, True)
    """,
    "octree_lod": f"""Nested LODs as the depths of an octree (a COPC file's): the points of depths 0 to d are
    the Poisson-disk set of radius ``spacing / 2**d`` in the metric among those of depth d + 1, and the
    deepest depth takes every point left, so each point has one depth.

    The octree is PDAL's: a cube from the points' lowest corner with their bounding box's longest side,
    ``spacing`` its side / 128, the spacing viewers assume for depth 0, halving per depth. The Poisson
    depths go on until the occupied cells of a depth's spacing are half as many as the points and no
    node of that depth holds more than 100,000 points. A cloud the root node takes whole has no Poisson
    depth and is not sampled: any number of points from one; a Poisson depth needs more points than the
    neighbours each normal and the geodesics are built from (21 with the defaults).

    Parameters
    ----------
    {INPUTS}
    {METRIC}
    {VISIT_ORDER}
    {RUN}

    Returns
    -------
    OctreeLod
        ``depth`` per point, the ``octree``, the ``radii`` per depth.

    {RAISES}

    Examples
    --------
    >>> import numpy as np, geodesic_lod as gl
    >>> rng = np.random.default_rng(0)
    >>> lod = gl.octree_lod(np.column_stack([rng.random((4000, 2)) * 100, np.zeros(4000)]))
    >>> cut = lod.cut(1)  # the nested LOD of radius lod.radii[1]
    >>> len(cut) < 4000, bool(np.all(lod.depth[cut] <= 1))
    (True, True)
    """,
    "write_copc": f"""Writes a LAS/LAZ file as a COPC file whose octree depths are ``octree_lod``'s: every
    record once, in the node of its depth that contains it, as ``geodesic-lod IN -o OUT.copc.laz`` writes it.

    Records of point formats 6 to 8 are kept bit for bit, those of 0 to 5 converted to 6 or 7 (COPC allows
    no other); the header's fields and the input's own VLRs and EVLRs (CRS, extra bytes) are kept. The
    file is written under a temporary name beside ``output`` and renamed once complete; the input is
    never modified.

    Parameters
    ----------
    input : str or path
        A LAS or LAZ file (COPC too).
    output : str or path
        The COPC file, named ``*.copc.laz``; never an input.
    metric, adaptivity, recompute_normals, visit_order, seed, threads, progress
        As in ``octree_lod``.
    overwrite : bool
        Replace ``output`` if it exists, or if another program or run makes it while this one works.
        Default False: the file found there is left as it is.

    Returns
    -------
    OctreeLod
        Each record's depth, the octree and the radii.

    Raises
    ------
    PointFileError
        A file that cannot be read or written (a ValueError naming it), before any work; after it, a file
        another program or run made at ``output`` meanwhile.
    InputError
        A bad argument.
    """,
    "OctreeLod": """What ``octree_lod`` returns.

    Attributes
    ----------
    octree : copc_files.Octree
        The cube: ``center``, ``halfsize`` and ``spacing`` (depth 0's point spacing).
    depth : (n,) ndarray of int32
        Per input row, its depth: 0 for the coarsest LOD's points, ``len(radii)`` for those in no LOD.
    radii : list of float
        Per Poisson depth d, the radius of its LOD, ``octree.spacing / 2**d``, in the metric.
    metric : str
        The metric the depths were sampled in: the one asked for, or the automatic choice ('' where no
        depth was sampled).
    visit_order : str
        Their visiting order, as asked or automatically chosen ('' where no depth was sampled).
    scatter_share : float
        As in ``PoissonLod``: the share the automatic choices followed (0 where no depth was sampled).
    """,
    "Domain": f"""One input's normals, curvature (eq. 1) and geodesic structure, built once for several LODs.

    The arrays are copied: changing them afterwards changes nothing here. The domain holds its memory
    (``nbytes``, a few hundred bytes a point) until it is dropped.

    Parameters
    ----------
    {INPUTS}
    {FACES}
    {METRIC}
    threads, progress
        As in ``poisson_lod``.

    {RAISES}
    """,
    "Lod": f"""What every sampler returns. Arrays are new numpy arrays; the input is never modified.

    {LOD_ATTRIBUTES}
    """,
    "PoissonLod": f"""What ``poisson_lod`` returns: a Lod and its Poisson set's radii.

    {LOD_ATTRIBUTES}
    radius : float
        The radius of the Poisson set the samples are (or were trimmed from), in the metric: the input's
        units, stretched by the metric's weights. 0 when a count was trimmed from all the points, or every
        point was asked for (each its own disk).
    covering_radius : float
        Every point lies within this distance in the metric (the input's units, weighted) of a sample: the
        exact largest one when trimmed, else ``radius``.
    iterations : int
        Poisson runs made (more than one when a count was asked).
    poisson_count : int
        Samples of the Poisson set before a trim.
    trimmed : bool
        Whether the set was thinned to the count (the samples nearest to others taken out first).
    visit_order : str
        The visiting order the disks took: the one asked for, or the automatic choice.
    """,
    "FpsLod": f"""What ``fps_lod`` returns: a Lod in farthest-point order; its first k samples are the k-sample LOD.

    {LOD_ATTRIBUTES}
    covering_radii : (k,) ndarray of float64
        ``covering_radii[j]``: the largest distance in the metric (the input's units, weighted) from a
        point to the first j + 1 samples; never rising, infinite while a connected part has no sample.
    covering_radius : float
        ``covering_radii[-1]``: every point lies within it of a sample (read-only).
    """,
    "LodPyramid": f"""What ``lod_pyramid`` returns: a Lod whose first ``counts[j]`` samples are level j.

    Attributes
    ----------
    {LOD_SAMPLES}
    faces : (0, 3) ndarray of int64
        Empty: each level's triangles are in ``level_faces``.
    positions : (k, 3) ndarray of float64
        Each sample's position, in the input's units: its input point, or with ``mesh_output`` the finest
        level's ``level_positions``.
    region_of : (0,) ndarray of int64
        Empty: a pyramid reports no regions.
    {LOD_DOMAIN}
    counts : list of int
        Samples per level, finest first, strictly decreasing.
    level_faces : list of (f_j, 3) ndarray of int64
        With ``mesh_output``: per level, its triangles, as rows of ``indices`` (below ``counts[j]``); else
        empty.
    level_positions : list of (counts[j], 3) ndarray of float64
        With ``mesh_output``: per level, its vertices' positions in the input's units, placed for that level
        (``placement``); else empty.
    radius : float
        The radius of the finest level's Poisson set, in the metric (the input's units, weighted).
    iterations : int
        Poisson runs made for the finest level.
    visit_order : str
        The visiting order every level's disks took: the one asked for, or the automatic choice.
    levels : list of (counts[j],) ndarray of int64
        Per level, finest first, its rows of the input, ``indices[:counts[j]]``: each a subset of the finer
        ones (read-only).
    """,
    "NormalVariation": """What ``normal_variation`` returns, per input row (n of them).

    Attributes
    ----------
    curvature : (n,) ndarray of float64
        v_i (eq. 1): the normal variation around each point, no unit, 0 on a plane, at most 1.
    normals : (n, 3) ndarray of float64
        n_i, of unit length: the input's, or estimated.
    estimated_normals : int
        Normals estimated from the points (the others are the input's).
    """,
    "HeightFieldLod": """A height-field LOD; every prefix of ``indices`` from ``hull_size`` on is an LOD of its own
    (k: the samples).

    Attributes
    ----------
    indices : (k,) ndarray of int64
        Rows of the input chosen: the corners of its convex hull in x, y, then in insertion order.
    errors : (k,) ndarray of float64
        Per sample, its height above or below the TIN of the samples before it, in the input's z units: the
        error its insertion removed (0 for the hull's corners).
    faces : (f, 3) ndarray of int64
        The Delaunay TIN in x, y of all samples, as rows of ``indices``, counter-clockwise seen from +z.
    hull_size : int
        Corners of the points' convex hull in x, y: the first samples.
    area : float
        The area of that hull, in the input's x, y units squared.
    separated_prefix : int
        The samples up to this many keep their disks: all of them, unless the points cover too little of
        their hull to hold that many disks (then the rest go by error alone).
    points : (n, 3) ndarray of float32 or float64
        The input points (not copied), for ``tin``.
    """,
}


def documented(fn, name: str = ""):
    """fn with its docstring from TEXTS (by `name`, else fn's own name)."""
    fn.__doc__ = TEXTS[name or fn.__name__]
    return fn
