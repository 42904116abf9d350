/* Measured media presets by name: Jensen2001's table (Fig. 5) and the
 * Narasimhan2006 media, in mm^-1, with the anisotropy folded into the
 * reduced scattering coefficient (so g = 0 reproduces them). */
#ifndef SUBSURF_MEDIA_H
#define SUBSURF_MEDIA_H

#include <stddef.h>

typedef struct {
  const char *name;
  double sigma_s_prime[3]; /* reduced scattering, RGB, mm^-1 */
  double sigma_a[3];       /* absorption, RGB, mm^-1 */
  double eta;              /* relative index the measurement assumed */
  const char *source;      /* citation */
} ss_medium_preset;

/* Case-insensitive lookup; NULL when the name is unknown. */
const ss_medium_preset *ss_medium_preset_find(const char *name);
size_t ss_medium_preset_count(void);
const ss_medium_preset *ss_medium_preset_at(size_t i);

#endif
