"""MeshLab's Quadric Edge Collapse Decimation asked for a vertex count: it takes a face count, so the
target is stepped by twice the vertices missing (a mesh with boundaries keeps more vertices per face)
until the vertices are within a tolerance of the count."""


def quadric_to_count(new_meshset, n, tolerance, **options):
    """(vertices, faces) of the decimated mesh: new_meshset() gives a MeshSet holding the input as its
    current mesh; options go to meshing_decimation_quadric_edge_collapse."""
    faces = 2 * n
    for _ in range(8):
        ms = new_meshset()
        ms.meshing_decimation_quadric_edge_collapse(targetfacenum=faces, **options)
        ms.meshing_remove_unreferenced_vertices()
        m = ms.current_mesh()
        if abs(m.vertex_number() - n) <= tolerance * n:
            break
        faces += 2 * (n - m.vertex_number())
    return m.vertex_matrix(), m.face_matrix()
