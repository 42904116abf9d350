/* The surface materials beyond diffuse (conductor, mirror, thin dielectric,
 * diffuse transmission, two-sided, mix): their BSDFs from the material's
 * fields, for material.c. */
#ifndef SUBSURF_RENDER_MATERIAL_SURFACE_H
#define SUBSURF_RENDER_MATERIAL_SURFACE_H

#include "subsurf/material.h"

/* 1 for the kinds this file builds. */
int ss_material_is_surface_kind(ss_material_kind kind);
/* Validates and builds m->bsdf (two-sided and mix: validates only, their
 * BSDF is built by ss_material_link); messages name the material. */
ss_status ss_material_surface_init(ss_material *m, ss_error *err);

#endif
