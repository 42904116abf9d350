#include "cli/majorant_warning.h"

#include "subsurf/volume.h"

int ss_cli_warn_majorant(FILE *out, const char *command, const ss_scene *scene) {
  int media = 0;
  for (size_t i = 0; i < scene->num_media; ++i) {
    uint64_t above = ss_medium_majorant_exceeded(&scene->media[i]);
    if (above > 0) {
      fprintf(out,
              "subsurf %s: warning: medium '%s': %llu tracking collisions found sigma_t above "
              "the majorant (the image is biased)\n",
              command, scene->media[i].name, (unsigned long long)above);
      ++media;
    }
  }
  return media;
}
