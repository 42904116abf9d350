/* gmsh's C API loaded on first use (dlopen) instead of linked: libgmsh
 * pulls in OpenCASCADE and FLTK, whose start-up costs every process that
 * links it about 0.8 s, and every `subsurf` command would pay it. Each
 * member has the type of the function declared in gmshc.h. */
#ifndef SUBSURF_FEM_GMSH_API_H
#define SUBSURF_FEM_GMSH_API_H

#include "subsurf/status.h"

#include <gmshc.h>

#define SS_GMSH_FUNCTIONS(X)                                                                       \
  X(gmshInitialize)                                                                                \
  X(gmshFinalize)                                                                                  \
  X(gmshFree)                                                                                      \
  X(gmshLoggerGetLastError)                                                                        \
  X(gmshOptionSetNumber)                                                                           \
  X(gmshModelAdd)                                                                                  \
  X(gmshModelGetEntities)                                                                          \
  X(gmshModelAddDiscreteEntity)                                                                    \
  X(gmshModelMeshAddNodes)                                                                         \
  X(gmshModelMeshAddElementsByType)                                                                \
  X(gmshModelMeshRemoveDuplicateNodes)                                                             \
  X(gmshModelMeshClassifySurfaces)                                                                 \
  X(gmshModelMeshCreateGeometry)                                                                   \
  X(gmshModelMeshFieldAdd)                                                                         \
  X(gmshModelMeshFieldSetString)                                                                   \
  X(gmshModelMeshFieldSetAsBackgroundMesh)                                                         \
  X(gmshModelMeshSetSizeCallback)                                                                  \
  X(gmshModelMeshGenerate)                                                                         \
  X(gmshModelMeshGetNodes)                                                                         \
  X(gmshModelMeshGetElementsByType)                                                                \
  X(gmshModelOccAddBox)                                                                            \
  X(gmshModelOccSynchronize)                                                                       \
  X(gmshModelGeoAddSurfaceLoop)                                                                    \
  X(gmshModelGeoAddVolume)                                                                         \
  X(gmshModelGeoSynchronize)

#define SS_GMSH_MEMBER(f) __typeof__(f) *f;
typedef struct {
  SS_GMSH_FUNCTIONS(SS_GMSH_MEMBER)
} ss_gmsh_api;
#undef SS_GMSH_MEMBER

/* The loaded API (kept for the process's life), or an error naming the
 * library and what is missing. Not thread-safe, like gmsh itself. */
ss_status ss_gmsh_api_get(const ss_gmsh_api **api, ss_error *err);

#endif
