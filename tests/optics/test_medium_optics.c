/* The shared description of a medium: presets convert with the similarity
 * relation, and the check names the field and channel at fault. */
#include "subsurf/medium_optics.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

Test(medium_optics, preset_keeps_the_reduced_scattering_for_any_g) {
  const ss_medium_preset *skin = ss_medium_preset_find("Skin1");
  cr_assert(skin != NULL);
  ss_medium_optics m = ss_medium_optics_from_preset(skin, 2.0, 0.8, SS_PHASE_HG);
  for (int c = 0; c < 3; ++c) {
    cr_expect_float_eq((1.0 - m.g.c[c]) * m.sigma_s.c[c], 2.0 * skin->sigma_s_prime[c], 1e-12);
    cr_expect_eq(m.sigma_a.c[c], 2.0 * skin->sigma_a[c]);
  }
  cr_expect_eq(m.phase, SS_PHASE_HG);
  cr_expect_eq(ss_medium_optics_check(&m, NULL), SS_OK);
}

Test(medium_optics, check_names_the_field_and_channel) {
  ss_error err;
  ss_medium_optics m = ss_medium_optics_gray(1.0, 0.1, 0.0, SS_PHASE_ISOTROPIC);
  cr_expect_eq(ss_medium_optics_check(&m, &err), SS_OK);
  m.sigma_a.c[1] = -1.0;
  cr_expect_eq(ss_medium_optics_check(&m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "sigma_a[G] must be finite and >= 0, got -1"), "%s", err.message);
  m = ss_medium_optics_gray(1.0, 0.1, 0.5, SS_PHASE_ISOTROPIC);
  cr_expect_eq(ss_medium_optics_check(&m, &err), SS_ERR_INVALID_ARGUMENT);
  m.sigma_s.c[2] = NAN;
  m.phase = SS_PHASE_HG;
  cr_expect_eq(ss_medium_optics_check(&m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "sigma_s[B]"), "%s", err.message);
  m = ss_medium_optics_gray(0.0, 0.0, 0.0, SS_PHASE_HG);
  cr_expect_eq(ss_medium_optics_check(&m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "sigma_s + sigma_a of channel R"), "%s", err.message);
}
