#ifndef GEODESIC_LOD_MESHLAB_MESH_H
#define GEODESIC_LOD_MESHLAB_MESH_H
// MeshLab's mesh type (CMeshO, Scalarm) and exception, for either API version.
#ifdef GEODESIC_LOD_MESHLAB_2020
#include <common/ml_mesh_type.h>
#else
#include <common/ml_document/cmesh.h>
#endif
#include <common/mlexception.h>
#endif
