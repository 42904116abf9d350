#include "cli/medium_options.h"

#include "subsurf/sampling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEG (SS_PI / 180.0)

const char *ss_channel_name(int c) {
  switch (c) {
  case 0:
    return "r";
  case 1:
    return "g";
  case 2:
    return "b";
  default:
    return "rgb";
  }
}

void ss_medium_options_init(ss_medium_options *o) {
  memset(o, 0, sizeof *o);
  ss_halfspace_params_default(&o->params);
  o->scale = 1.0;
  o->channel = 0;
  o->sigma_s = o->params.medium.sigma_s.c[0];
  o->sigma_a = o->params.medium.sigma_a.c[0];
  o->g = o->params.medium.g.c[0];
  /* The paper's exponent; flakes about the surface normal. */
  o->flakes = (ss_medium_flakes){
      .type = SS_FLAKE_NONE, .p = 20.0, .axis = {0.0, 0.0, 1.0}, .albedo_exponent = 1.0};
}

/* --medium-axis x,y,z: the flakes' axis; its length does not matter. */
static int parse_axis(const char *cmd, const char *value, ss_vec3 *axis) {
  double v[3];
  if (ss_cli_number_list(value, -1e6, 1e6, v, 3) != 3 ||
      v[0] * v[0] + v[1] * v[1] + v[2] * v[2] < 1e-24) {
    fprintf(stderr,
            "subsurf %s: --medium-axis: expected three numbers x,y,z, not all zero, got '%s'\n",
            cmd, value);
    return -1;
  }
  *axis = ss_vec3_make(v[0], v[1], v[2]);
  return 0;
}

/* The micro-flake options; 0 when `name` is not one of them. */
static int parse_flakes(ss_medium_options *o, const char *cmd, const char *name, const char *value,
                        int *rc) {
  ss_medium_flakes *f = &o->flakes;
  if (!strcmp(name, "flakes")) {
    if (!ss_flake_type_from_name(value, &f->type)) {
      fprintf(stderr, "subsurf %s: --flakes: expected none, uniform, surface or fiber, got '%s'\n",
              cmd, value);
      *rc = -1;
    }
  } else if (!strcmp(name, "flake-p")) {
    *rc = ss_parse_double_in(cmd, name, value, 0.0, 1000.0, &f->p);
  } else if (!strcmp(name, "medium-axis")) {
    *rc = parse_axis(cmd, value, &f->axis);
  } else if (!strcmp(name, "flake-albedo-falloff")) {
    *rc = ss_parse_double_in(cmd, name, value, 0.0, 1.0, &f->albedo_falloff);
  } else if (!strcmp(name, "flake-albedo-exponent")) {
    *rc = ss_parse_double_in(cmd, name, value, 0.0, 100.0, &f->albedo_exponent);
  } else {
    return 0;
  }
  return 1;
}

/* A number of ss_halfspace_args, the grammar the flat interface reads too. */
static int number(const char *cmd, const char *name, const char *value, double *out) {
  return ss_parse_arg(cmd, ss_halfspace_args, name, value, out);
}

/* A whole number of ss_halfspace_args that fits an int (its range does). */
static int whole(const char *cmd, const char *name, const char *value, int *out) {
  double v;
  if (number(cmd, name, value, &v) != 0) {
    return -1;
  }
  *out = (int)v;
  return 0;
}

/* A whole number of ss_halfspace_args in the range of uint64_t. */
static int whole_u64(const char *cmd, const char *name, const char *value, uint64_t *out) {
  double v;
  if (number(cmd, name, value, &v) != 0) {
    return -1;
  }
  *out = (uint64_t)v;
  return 0;
}

static int parse_degrees(const char *cmd, const char *name, const char *value, double *out) {
  double deg;
  if (number(cmd, name, value, &deg) != 0) {
    return -1;
  }
  *out = deg * DEG;
  return 0;
}

int ss_medium_options_parse(ss_medium_options *o, const char *cmd, const char *name,
                            const char *value) {
  ss_halfspace_params *p = &o->params;
  int rc = 0;
  if (!strcmp(name, "sigma-s")) {
    rc = number(cmd, name, value, &o->sigma_s);
    o->sigma_s_set = 1;
  } else if (!strcmp(name, "sigma-a")) {
    rc = number(cmd, name, value, &o->sigma_a);
    o->sigma_a_set = 1;
  } else if (!strcmp(name, "g")) {
    rc = number(cmd, name, value, &o->g);
  } else if (!strcmp(name, "phase")) {
    if (!ss_phase_type_from_name(value, &p->medium.phase)) {
      fprintf(stderr, "subsurf %s: --phase: expected iso, hg or gauss, got '%s'\n", cmd, value);
      rc = -1;
    }
  } else if (!strcmp(name, "eta")) {
    rc = number(cmd, name, value, &p->eta);
    o->eta_set = 1;
  } else if (!strcmp(name, "theta-i")) {
    rc = parse_degrees(cmd, name, value, &p->theta_i);
  } else if (!strcmp(name, "thickness")) {
    rc = number(cmd, name, value, &p->thickness);
  } else if (!strcmp(name, "medium")) {
    o->medium = ss_medium_preset_find(value);
    if (!o->medium) {
      fprintf(stderr, "subsurf %s: --medium: unknown medium '%s'; known media:", cmd, value);
      for (size_t i = 0; i < ss_medium_preset_count(); ++i) {
        fprintf(stderr, "%s '%s'", i ? "," : "", ss_medium_preset_at(i)->name);
      }
      fprintf(stderr, "\n");
      rc = -1;
    }
  } else if (!strcmp(name, "scale")) {
    rc = ss_parse_double(cmd, name, value, &o->scale);
    if (rc == 0 && !(o->scale > 0.0 && o->scale <= SS_HALFSPACE_MAX_COEFF)) {
      fprintf(stderr, "subsurf %s: --scale: expected a number in (0, %g], got '%s'\n", cmd,
              SS_HALFSPACE_MAX_COEFF, value);
      rc = -1;
    }
  } else if (!strcmp(name, "channel")) {
    o->channel_set = 1;
    if (!strcmp(value, "r")) {
      o->channel = 0;
    } else if (!strcmp(value, "g")) {
      o->channel = 1;
    } else if (!strcmp(value, "b")) {
      o->channel = 2;
    } else if (!strcmp(value, "rgb")) {
      o->channel = SS_CHANNEL_ALL;
    } else {
      fprintf(stderr, "subsurf %s: --channel: expected r, g, b or rgb, got '%s'\n", cmd, value);
      rc = -1;
    }
  } else if (!strcmp(name, "rmin")) {
    rc = number(cmd, name, value, &p->rmin);
  } else if (!strcmp(name, "rmax")) {
    rc = number(cmd, name, value, &p->rmax);
  } else if (!strcmp(name, "rbins")) {
    rc = whole(cmd, name, value, &p->rbins);
  } else if (!strcmp(name, "theta-o")) {
    if (p->n_theta_o >= SS_HALFSPACE_MAX_DIRECTIONS) {
      fprintf(stderr, "subsurf %s: --theta-o: at most %d directions\n", cmd,
              SS_HALFSPACE_MAX_DIRECTIONS);
      rc = -1;
    } else {
      rc = parse_degrees(cmd, name, value, &p->theta_o[p->n_theta_o++]);
    }
  } else if (!strcmp(name, "xmin")) {
    rc = number(cmd, name, value, &p->xmin);
  } else if (!strcmp(name, "xmax")) {
    rc = number(cmd, name, value, &p->xmax);
  } else if (!strcmp(name, "xbins")) {
    rc = whole(cmd, name, value, &p->xbins);
  } else if (!strcmp(name, "ymin")) {
    rc = number(cmd, name, value, &p->ymin);
  } else if (!strcmp(name, "ymax")) {
    rc = number(cmd, name, value, &p->ymax);
  } else if (!strcmp(name, "ybins")) {
    rc = whole(cmd, name, value, &p->ybins);
  } else if (!parse_flakes(o, cmd, name, value, &rc)) {
    return 0;
  }
  return rc == 0 ? 1 : -1;
}

int ss_medium_options_parse_run(ss_medium_options *o, const char *cmd, const char *name,
                                const char *value) {
  ss_halfspace_params *p = &o->params;
  int rc;
  if (!strcmp(name, "paths")) {
    rc = whole_u64(cmd, name, value, &p->paths);
  } else if (!strcmp(name, "time-limit")) {
    rc = number(cmd, name, value, &p->time_limit);
  } else if (!strcmp(name, "seed")) {
    rc = whole_u64(cmd, name, value, &p->seed);
  } else if (!strcmp(name, "threads")) {
    rc = whole(cmd, name, value, &p->threads);
  } else if (!strcmp(name, "max-depth")) {
    rc = whole_u64(cmd, name, value, &p->max_depth);
  } else {
    return 0;
  }
  return rc == 0 ? 1 : -1;
}

int ss_medium_options_finish(ss_medium_options *o, const char *cmd) {
  if (o->medium && (o->sigma_s_set || o->sigma_a_set)) {
    fprintf(stderr,
            "subsurf %s: --medium: give either a named medium or --sigma-s/--sigma-a, "
            "not both\n",
            cmd);
    return -1;
  }
  if (!o->medium && o->channel_set && o->channel != 0) {
    fprintf(stderr, "subsurf %s: --channel: only meaningful with --medium NAME\n", cmd);
    return -1;
  }
  if (o->medium && !o->eta_set) {
    o->params.eta = o->medium->eta;
  }
  for (int i = 0; i < ss_medium_options_channel_count(o); ++i) {
    ss_medium_options_select_channel(o, ss_medium_options_channel_at(o, i));
    ss_error err;
    if (ss_halfspace_validate(&o->params, &err) != SS_OK) {
      fprintf(stderr, "subsurf %s: --%s\n", cmd, err.message);
      return -1;
    }
  }
  return 0;
}

void ss_medium_options_select_channel(ss_medium_options *o, int c) {
  ss_phase_type phase = o->params.medium.phase;
  if (!o->medium) {
    o->params.medium = ss_medium_optics_gray(o->sigma_s, o->sigma_a, o->g, phase);
    o->params.medium.flakes = o->flakes;
    o->params.channel = 0;
    return;
  }
  /* Presets give the reduced coefficient sigma_s'; with a chosen g,
   * sigma_s = sigma_s' / (1 - g) keeps the measured sigma_s'. */
  o->params.medium = ss_medium_optics_from_preset(o->medium, o->scale, o->g, phase);
  o->params.medium.flakes = o->flakes;
  o->params.channel = c;
}

int ss_medium_options_channel_count(const ss_medium_options *o) {
  return o->channel == SS_CHANNEL_ALL ? 3 : 1;
}

int ss_medium_options_channel_at(const ss_medium_options *o, int i) {
  return o->channel == SS_CHANNEL_ALL ? i : o->channel;
}

void ss_medium_options_help(FILE *out) {
  ss_halfspace_params d;
  ss_halfspace_params_default(&d);
  fprintf(out,
          "medium:\n"
          "  --sigma-s X        scattering coefficient per unit length, [0, 1e6] (default %g)\n"
          "  --sigma-a X        absorption coefficient per unit length, [0, 1e6] (default %g)\n"
          "  --g X              mean cosine of the phase function, -1 < g < 1 (default %g)\n"
          "  --phase NAME       iso | hg | gauss (default iso)\n"
          "  --medium NAME      a measured medium (mm^-1, Jensen et al. 2001 and Narasimhan et\n"
          "                     al. 2006); sets sigma_s = sigma_s'/(1-g), sigma_a, and eta unless\n"
          "                     --eta is given (default: none)\n"
          "  --scale X          multiplies the medium's coefficients (default 1)\n"
          "  --channel C        r | g | b | rgb: which colour of --medium (default r)\n"
          "  --flakes TYPE      none | uniform | surface | fiber: a micro-flake medium (Jakob et\n"
          "                     al. 2010) whose flakes' normals follow D ~ |cos(axis, m)|^p\n"
          "                     (surface) or |sin(axis, m)|^p (fiber); extinction depends on the\n"
          "                     direction. sigma-s and sigma-a are those of the same flakes\n"
          "                     oriented uniformly (isotropic); --g must be 0 (default none)\n"
          "  --flake-p P        the distribution's exponent, [0, 1000] (default 20)\n"
          "  --medium-axis X,Y,Z  the flakes' axis (any length; default 0,0,1, the normal)\n"
          "  --flake-albedo-falloff F  flake albedo alpha (1 - F + F |w.m|^K): F in [0, 1]\n"
          "                     (default 0: constant albedo sigma-s/(sigma-s + sigma-a))\n"
          "  --flake-albedo-exponent K  K in [0, 100] (default 1)\n"
          "boundary and incidence:\n"
          "  --eta X            n_inside / n_outside, [0.1, 10]; 1 is index matched (default %g)\n"
          "  --theta-i DEG      polar angle of the beam, tilted toward +x (default 0)\n"
          "  --thickness X      slab thickness; inf for a half-space (default inf)\n"
          "outputs' binning:\n"
          "  --rmin X --rmax X  radial bins: [0, rmin) then log-spaced to rmax (default %g, %g)\n"
          "  --rbins N          number of radial bins (default %d)\n"
          "  --theta-o DEG      an exact outgoing direction in the x-z plane, positive toward\n"
          "                     +x; repeatable (default: none)\n"
          "  --xmin X --xmax X  x range of direction slices and the map (default %g, %g)\n"
          "  --xbins N          (default %d)\n"
          "  --ymin X --ymax X  y range of the map (default %g, %g)\n"
          "  --ybins N          (default %d)\n"
          "Lengths (thickness, bin ranges, radii) lie within +-1e6; see README, Limits.\n",
          d.medium.sigma_s.c[0], d.medium.sigma_a.c[0], d.medium.g.c[0], d.eta, d.rmin, d.rmax,
          d.rbins, d.xmin, d.xmax, d.xbins, d.ymin, d.ymax, d.ybins);
}

cJSON *ss_medium_options_to_json(const ss_medium_options *o) {
  const ss_halfspace_params *p = &o->params;
  cJSON *j = cJSON_CreateObject();
  if (o->medium) {
    cJSON_AddStringToObject(j, "medium", o->medium->name);
    cJSON_AddNumberToObject(j, "scale", o->scale);
  }
  cJSON_AddStringToObject(j, "channel", ss_channel_name(o->channel));
  if (o->channel == SS_CHANNEL_ALL) {
    /* One value per colour; each channel's own "params" has its pair. */
    ss_medium_options each = *o;
    cJSON *ss = cJSON_AddArrayToObject(j, "sigma_s"), *sa = cJSON_AddArrayToObject(j, "sigma_a");
    for (int c = 0; c < 3; ++c) {
      ss_medium_options_select_channel(&each, c);
      cJSON_AddItemToArray(ss, cJSON_CreateNumber(each.params.medium.sigma_s.c[c]));
      cJSON_AddItemToArray(sa, cJSON_CreateNumber(each.params.medium.sigma_a.c[c]));
    }
  } else {
    cJSON_AddNumberToObject(j, "sigma_s", p->medium.sigma_s.c[p->channel]);
    cJSON_AddNumberToObject(j, "sigma_a", p->medium.sigma_a.c[p->channel]);
  }
  cJSON_AddNumberToObject(j, "g", o->g);
  cJSON_AddStringToObject(j, "phase", ss_phase_type_name(p->medium.phase));
  const ss_medium_flakes *f = &o->flakes;
  if (f->type != SS_FLAKE_NONE) {
    cJSON_AddStringToObject(j, "flakes", ss_flake_type_name(f->type));
    cJSON_AddNumberToObject(j, "flake_p", f->p);
    cJSON *axis = cJSON_AddArrayToObject(j, "medium_axis");
    cJSON_AddItemToArray(axis, cJSON_CreateNumber(f->axis.x));
    cJSON_AddItemToArray(axis, cJSON_CreateNumber(f->axis.y));
    cJSON_AddItemToArray(axis, cJSON_CreateNumber(f->axis.z));
    cJSON_AddNumberToObject(j, "flake_albedo_falloff", f->albedo_falloff);
    cJSON_AddNumberToObject(j, "flake_albedo_exponent", f->albedo_exponent);
  }
  cJSON_AddNumberToObject(j, "eta", p->eta);
  cJSON_AddNumberToObject(j, "theta_i", p->theta_i / DEG);
  if (isfinite(p->thickness)) {
    cJSON_AddNumberToObject(j, "thickness", p->thickness);
  } else {
    cJSON_AddStringToObject(j, "thickness", "inf");
  }
  cJSON_AddNumberToObject(j, "rmin", p->rmin);
  cJSON_AddNumberToObject(j, "rmax", p->rmax);
  cJSON_AddNumberToObject(j, "rbins", p->rbins);
  cJSON *th = cJSON_AddArrayToObject(j, "theta_o");
  for (int i = 0; i < p->n_theta_o; ++i) {
    cJSON_AddItemToArray(th, cJSON_CreateNumber(p->theta_o[i] / DEG));
  }
  cJSON_AddNumberToObject(j, "xmin", p->xmin);
  cJSON_AddNumberToObject(j, "xmax", p->xmax);
  cJSON_AddNumberToObject(j, "xbins", p->xbins);
  cJSON_AddNumberToObject(j, "ymin", p->ymin);
  cJSON_AddNumberToObject(j, "ymax", p->ymax);
  cJSON_AddNumberToObject(j, "ybins", p->ybins);
  return j;
}
