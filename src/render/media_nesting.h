/* Which media touch or nest (private to src/render): checked when a scene
 * is committed, so that paths carry a stack of media only where needed. */
#ifndef SUBSURF_RENDER_MEDIA_NESTING_H
#define SUBSURF_RENDER_MEDIA_NESTING_H

#include "subsurf/scene.h"

/* Relates the pairs of shapes bounding an interface's region whose bounds
 * meet (box_overlaps.h; then mesh_apart.h: apart by more than 1e-6 of the
 * larger one's size). Overlapping regions of two materials need different
 * priorities, an index each (an index-matched material may overlap only one
 * of index 1) and constant coefficients; no SS_MEDIUM_STACK_SIZE + 1 regions
 * may all overlap one another (a path's stack holds that many). Sets
 * s->nested_material (-1 when all are apart) and, when some overlap,
 * s->camera_media. The messages name the shapes, materials and keys. */
ss_status ss_scene_check_media(ss_scene *s, ss_error *err);

#endif
