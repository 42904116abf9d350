/* Which pixels see a translucent object: the material of the camera ray's
 * first hit through each pixel's centre (rays cross index-matched
 * interfaces that enclose no medium). */
#ifndef SUBSURF_TRANSLUCENT_MASK_H
#define SUBSURF_TRANSLUCENT_MASK_H

#include "subsurf/image.h"
#include "subsurf/scene.h"
#include "subsurf/status.h"

/* A width x height x 1 image of the committed scene's camera: 1 where the
 * first hit is a translucent material (an interface enclosing a medium),
 * else 0. SS_ERR_NO_MEMORY, or SS_ERR_INVALID_ARGUMENT for a scene not
 * committed. */
ss_status ss_translucent_mask(const ss_scene *scene, ss_image **out, ss_error *err);

#endif
