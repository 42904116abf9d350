/* subsurf fem: the diffusion equation on a tetrahedral mesh
 * (docs/fem.md): mesh a box or a closed triangle mesh with gmsh, assemble,
 * solve with CHOLMOD or CG, write the fluence and exitance per vertex as a
 * PLY and a summary as JSON. */
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/fem_volume.h"
#include "cli/output_check.h"
#include "cli/result_json.h"

#include "subsurf/fem.h"
#include "subsurf/fem_io.h"
#include "subsurf/flake_diffusion.h"
#include "subsurf/media.h"
#include "subsurf/mesh.h"
#include "subsurf/mesh_io.h"
#include "subsurf/progress.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CMD "fem"
#define MAX_PROFILE 64

typedef struct {
  double sigma_s, sigma_a, g, eta, scale;
  const ss_medium_preset *preset;
  int channel, eta_set;
  ss_flake_type flakes;
  double flake_p, axis[3];
  double box[3];
  int box_set;
  const char *mesh_path;
  double spot[3], spot_radius, spot_power;
  int spot_set, spot_radius_set, point_source, boundary_source;
  const char *grid_path;
  double grid_offset[3], min_density;
  double size_near, size_far, refine_radius, rim_size, size_medium;
  int refine_radius_set;
  ss_fem_solve_options solve;
  const char *output, *json_path;
  double profile_r[MAX_PROFILE];
  int n_profile;
} options;

/* Ctrl-C or SIGTERM: gmsh and CHOLMOD cannot be stopped from outside, and
 * nothing is written before the solution is complete, so the process ends at
 * once (exit 130); during writing, the files begun are removed first. */
static const char *output_paths[2];
static volatile sig_atomic_t writing;

static void on_interrupt(int sig) {
  (void)sig;
  if (writing) {
    for (int i = 0; i < 2; ++i) {
      if (output_paths[i]) {
        unlink(output_paths[i]);
      }
    }
  }
  static const char msg[] = "subsurf " CMD ": interrupted; nothing written\n";
  ssize_t n = write(STDERR_FILENO, msg, sizeof msg - 1);
  (void)n;
  _exit(130);
}

static void exit_on_interrupt(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sigaddset(&sa.sa_mask, SIGINT);
  sigaddset(&sa.sa_mask, SIGTERM);
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
}

/* The library's "fem: " or "fem " prefix dropped from its message: the
 * command names it already ("subsurf fem: mesh: ..."). */
static void drop_library_prefix(ss_error *err) {
  size_t skip =
      !strncmp(err->message, "fem: ", 5) ? 5 : (!strncmp(err->message, "fem ", 4) ? 4 : 0);
  memmove(err->message, err->message + skip, strlen(err->message + skip) + 1);
}

/* A library error on one line. */
static void print_error(ss_error *err) {
  drop_library_prefix(err);
  fprintf(stderr, "subsurf " CMD ": %s\n", err->message);
}

static void usage(FILE *out) {
  fprintf(out,
          "usage: subsurf fem (--box W,H,D | --mesh FILE) --output FILE.ply [options]\n\n"
          "Solves the diffusion equation by finite elements (Jakob et al. 2010, sec. 6.2; see\n"
          "docs/fem.md) inside a box x in [-W/2, W/2], y in [-H/2, H/2], z in [-D, 0] or a\n"
          "closed triangle mesh (PLY or OBJ, wound outward), meshed into tetrahedra by gmsh,\n"
          "lit by a diffuse spot on its surface, and writes the fluence and the exitance at\n"
          "every vertex as a PLY (boundary triangles as faces).\n\n"
          "medium (lengths in any unit, coefficients per unit length):\n"
          "  --sigma-s X        scattering coefficient (default 1)\n"
          "  --sigma-a X        absorption coefficient (default 0.01)\n"
          "  --g X              mean cosine: sigma_s' = (1 - g) sigma_s (default 0)\n"
          "  --medium NAME      a measured medium (mm^-1; sets sigma_s' and sigma_a, and eta\n"
          "                     unless --eta is given)\n"
          "  --channel C        r | g | b: which colour of --medium (default r)\n"
          "  --scale X          multiplies the coefficients (default 1)\n"
          "  --eta X            n_inside / n_outside, [0.1, 10] (default 1.3)\n"
          "  --flakes TYPE      none | uniform | surface | fiber: a micro-flake medium (Jakob et\n"
          "                     al. 2010) with the diffusion matrix M of its eq. 34: sigma-s and\n"
          "                     sigma-a are those of the same flakes oriented uniformly, constant\n"
          "                     flake albedo; --g must be 0 (default none)\n"
          "  --flake-p P        the distribution's exponent, [0, 1000] (default 20)\n"
          "  --medium-axis X,Y,Z  the flakes' axis (default 0,0,1)\n"
          "  --grid FILE        a heterogeneous medium: a density grid (.ssgrid raw or .vdb\n"
          "                     OpenVDB, as the scene format's \"grid\": {\"file\"}) scaling\n"
          "                     the coefficients, its voxels' axes orienting the flakes\n"
          "  --grid-offset X,Y,Z  moves the grid's box (default 0,0,0)\n"
          "  --min-density F    densities below F times the grid's largest are raised to it\n"
          "                     (diffusion needs a scattering medium everywhere; default 0.01)\n"
          "geometry and mesh (sizes in transport mean free paths 1/sigma_t' at the grid's\n"
          "largest density):\n"
          "  --box W,H,D        a box, its top face z = 0\n"
          "  --mesh FILE        a closed triangle mesh (.ply or .obj)\n"
          "  --size-near F      element size at the source (default 0.25)\n"
          "  --size-far F       element size far from it (default 2)\n"
          "  --refine-radius F  radius of the fine region around the spot (default: the spot's\n"
          "                     radius + 1)\n"
          "  --size-rim F       element size along the spot's rim, growing by the distance from\n"
          "                     it (the edge of the source image; default: none)\n"
          "  --size-medium F    with --grid: element size where the medium varies fast (its\n"
          "                     coefficients change by 10 %% over less than the size), growing\n"
          "                     by half the distance from there (default: none)\n");
  fprintf(out,
          "source:\n"
          "  --spot X,Y,Z       the spot's centre on the surface (default: 0,0,0 for a box, the\n"
          "                     centre of the top of the bounding box for a mesh)\n"
          "  --spot-radius R    its radius in transport mean free paths (default 0.5)\n"
          "  --spot-power P     power refracted into the medium (default 1); its first\n"
          "                     scattering events are the source: P alpha' distributed as\n"
          "                     sigma exp(-sigma s) along cosine-distributed refracted rays\n"
          "                     from the spot (sigma = sigma_t' at the spot, alpha' = sigma_s'/\n"
          "                     sigma_t'; for flakes both along each ray, reduced by the\n"
          "                     similarity relation: sigma_t(w) (1 - alpha w.g(w)), g(w) the mean\n"
          "                     direction of once-scattered light)\n"
          "  --boundary-source  instead, the paper's boundary source (eq. 37-38): Gamma_s =\n"
          "                     P exp(-sigma_a/sigma_s') spread uniformly over the spot (its\n"
          "                     exitance turns negative on spots narrower than a mean free path)\n"
          "  --point-source     instead of the spot, the classical dipole's source: an\n"
          "                     isotropic point of power P alpha' one transport mean free path\n"
          "                     below the spot's centre (along -z)\n"
          "solver:\n"
          "  --solver NAME      cholmod (sparse Cholesky, default) | pcg (conjugate gradients,\n"
          "                     Jacobi preconditioner; less memory for large meshes)\n"
          "  --tolerance X      pcg: relative residual (default 1e-8)\n"
          "  --max-iterations N pcg (default 100000)\n"
          "outputs:\n"
          "  --output FILE      the PLY (required): x y z fluence exitance per vertex\n"
          "  --json FILE|-      sizes, times, energy balance and the profile (default: a summary\n"
          "                     on stdout)\n"
          "  --profile-r LIST   r1,r2,...: exitance at the spot's centre + (r, 0, 0) (lengths)\n");
}

static int parse_triple(const char *name, const char *value, double lo, double hi, double out[3]) {
  if (ss_cli_number_list(value, lo, hi, out, 3) != 3) {
    fprintf(stderr, "subsurf " CMD ": --%s: expected X,Y,Z with values in [%g, %g], got '%s'\n",
            name, lo, hi, value);
    return -1;
  }
  return 1;
}

static int parse_medium(options *o, const char *name, const char *value) {
  if (!strcmp(name, "sigma-s")) {
    return ss_parse_double_in(CMD, name, value, 0, 1e6, &o->sigma_s) ? -1 : 1;
  } else if (!strcmp(name, "sigma-a")) {
    return ss_parse_double_in(CMD, name, value, 0, 1e6, &o->sigma_a) ? -1 : 1;
  } else if (!strcmp(name, "g")) {
    return ss_parse_double_in(CMD, name, value, -0.999, 0.999, &o->g) ? -1 : 1;
  } else if (!strcmp(name, "eta")) {
    o->eta_set = 1;
    return ss_parse_double_in(CMD, name, value, 0.1, 10, &o->eta) ? -1 : 1;
  } else if (!strcmp(name, "scale")) {
    return ss_parse_double_in(CMD, name, value, 1e-6, 1e6, &o->scale) ? -1 : 1;
  } else if (!strcmp(name, "medium")) {
    o->preset = ss_medium_preset_find(value);
    if (!o->preset) {
      fprintf(stderr,
              "subsurf " CMD ": --medium: unknown medium '%s' (see subsurf halfspace "
              "--help)\n",
              value);
      return -1;
    }
    return 1;
  } else if (!strcmp(name, "flakes")) {
    const char *types[] = {"none", "uniform", "surface", "fiber"};
    for (int i = 0; i < 4; ++i) {
      if (!strcmp(value, types[i])) {
        o->flakes = (ss_flake_type)i;
        return 1;
      }
    }
    fprintf(stderr,
            "subsurf " CMD ": --flakes: expected none, uniform, surface or fiber, got '%s'\n",
            value);
    return -1;
  } else if (!strcmp(name, "flake-p")) {
    return ss_parse_double_in(CMD, name, value, 0, 1000, &o->flake_p) ? -1 : 1;
  } else if (!strcmp(name, "medium-axis")) {
    return parse_triple(name, value, -1e6, 1e6, o->axis);
  } else if (!strcmp(name, "grid")) {
    o->grid_path = value;
    return 1;
  } else if (!strcmp(name, "grid-offset")) {
    return parse_triple(name, value, -1e6, 1e6, o->grid_offset);
  } else if (!strcmp(name, "min-density")) {
    return ss_parse_double_in(CMD, name, value, 1e-6, 1, &o->min_density) ? -1 : 1;
  } else if (!strcmp(name, "channel")) {
    const char *names = "rgb";
    if (strlen(value) != 1 || !strchr(names, value[0])) {
      fprintf(stderr, "subsurf " CMD ": --channel: expected r, g or b, got '%s'\n", value);
      return -1;
    }
    o->channel = (int)(strchr(names, value[0]) - names);
    return 1;
  }
  return 0;
}

static int parse_own(void *ctx, const char *name, const char *value) {
  options *o = ctx;
  int rc = parse_medium(o, name, value);
  if (rc) {
    return rc;
  }
  if (!strcmp(name, "box")) {
    o->box_set = 1;
    return parse_triple(name, value, 1e-6, 1e6, o->box);
  } else if (!strcmp(name, "mesh")) {
    o->mesh_path = value;
  } else if (!strcmp(name, "spot")) {
    o->spot_set = 1;
    return parse_triple(name, value, -1e6, 1e6, o->spot);
  } else if (!strcmp(name, "spot-radius")) {
    o->spot_radius_set = 1;
    return ss_parse_double_in(CMD, name, value, 1e-6, 1e6, &o->spot_radius) ? -1 : 1;
  } else if (!strcmp(name, "spot-power")) {
    return ss_parse_double_in(CMD, name, value, 0, 1e12, &o->spot_power) ? -1 : 1;
  } else if (!strcmp(name, "size-near")) {
    return ss_parse_double_in(CMD, name, value, 1e-3, 1e3, &o->size_near) ? -1 : 1;
  } else if (!strcmp(name, "size-far")) {
    return ss_parse_double_in(CMD, name, value, 1e-3, 1e3, &o->size_far) ? -1 : 1;
  } else if (!strcmp(name, "size-rim")) {
    return ss_parse_double_in(CMD, name, value, 1e-3, 1e3, &o->rim_size) ? -1 : 1;
  } else if (!strcmp(name, "size-medium")) {
    return ss_parse_double_in(CMD, name, value, 1e-3, 1e3, &o->size_medium) ? -1 : 1;
  } else if (!strcmp(name, "refine-radius")) {
    o->refine_radius_set = 1;
    return ss_parse_double_in(CMD, name, value, 0, 1e6, &o->refine_radius) ? -1 : 1;
  } else if (!strcmp(name, "solver")) {
    if (!strcmp(value, "cholmod")) {
      o->solve.solver = SS_FEM_CHOLMOD;
    } else if (!strcmp(value, "pcg")) {
      o->solve.solver = SS_FEM_PCG;
    } else {
      fprintf(stderr, "subsurf " CMD ": --solver: expected cholmod or pcg, got '%s'\n", value);
      return -1;
    }
  } else if (!strcmp(name, "tolerance")) {
    return ss_parse_double_in(CMD, name, value, 1e-15, 0.5, &o->solve.tolerance) ? -1 : 1;
  } else if (!strcmp(name, "max-iterations")) {
    return ss_parse_int(CMD, name, value, 1, 100000000, &o->solve.max_iterations) ? -1 : 1;
  } else if (!strcmp(name, "output")) {
    o->output = value;
  } else if (!strcmp(name, "json")) {
    o->json_path = value;
  } else if (!strcmp(name, "profile-r")) {
    o->n_profile = ss_cli_number_list(value, 0, 1e6, o->profile_r, MAX_PROFILE);
    if (o->n_profile < 1) {
      fprintf(stderr,
              "subsurf " CMD ": --profile-r: expected up to %d radii r1,r2,... in "
              "[0, 1e6], got '%s'\n",
              MAX_PROFILE, value);
      return -1;
    }
  } else {
    return 0;
  }
  return 1;
}

static int parse_flag(void *ctx, const char *name) {
  options *o = ctx;
  if (!strcmp(name, "point-source")) {
    o->point_source = 1;
    return 1;
  }
  if (!strcmp(name, "boundary-source")) {
    o->boundary_source = 1;
    return 1;
  }
  return 0;
}

/* Returns 0, 1 after --help, or 2 on bad input (printed). */
static int parse_args(options *o, int argc, char **argv) {
  const ss_cli_spec spec = {parse_flag, parse_own, NULL, usage};
  int rc = ss_cli_parse(CMD, argc, argv, 1, &spec, o);
  if (rc != 0) {
    return rc;
  }
  if (o->box_set == !!o->mesh_path) {
    fprintf(stderr, "subsurf " CMD ": exactly one of --box and --mesh is required\n");
    return 2;
  }
  if (!o->output) {
    fprintf(stderr, "subsurf " CMD ": --output: missing; the PLY file is required\n");
    return 2;
  }
  if (o->size_near > o->size_far) {
    fprintf(stderr, "subsurf " CMD ": --size-near %g must not exceed --size-far %g\n", o->size_near,
            o->size_far);
    return 2;
  }
  if (o->point_source && o->rim_size > 0.0) {
    fprintf(stderr, "subsurf " CMD ": --size-rim: only with a spot (not with --point-source)\n");
    return 2;
  }
  if (o->size_medium > 0.0 && !o->grid_path) {
    fprintf(stderr, "subsurf " CMD ": --size-medium: only with --grid (a homogeneous medium "
                    "does not vary)\n");
    return 2;
  }
  if (o->point_source && o->boundary_source) {
    fprintf(stderr, "subsurf " CMD ": --boundary-source: not with --point-source (one source)\n");
    return 2;
  }
  if (o->point_source && o->mesh_path) {
    fprintf(stderr, "subsurf " CMD ": --point-source: only with --box (it lies along -z)\n");
    return 2;
  }
  ss_output_plan p;
  ss_output_plan_init(&p);
  ss_output_plan_add(&p, "--output", o->output, SS_FILE_PLY, 0, 0);
  if (o->json_path) {
    ss_output_plan_add(&p, "--json", o->json_path, SS_FILE_JSON, 0, 0);
  }
  if (o->mesh_path) {
    ss_output_plan_add_input(&p, "--mesh", o->mesh_path);
  }
  if (o->grid_path) {
    ss_output_plan_add_input(&p, "--grid", o->grid_path);
  }
  return ss_cli_check_outputs(&p, CMD);
}

/* The medium: isotropic, or the flakes' M and mu0, optionally on a grid;
 * 2 on bad input (printed). */
static int make_medium(const options *o, double sigma_s_prime, double sigma_a,
                       ss_cli_fem_medium *med) {
  if (o->flakes != SS_FLAKE_NONE && (o->g != 0.0 || o->preset)) {
    fprintf(stderr, "subsurf " CMD ": --flakes: needs --g 0 and --sigma-s/--sigma-a (the flakes "
                    "scatter specularly)\n");
    return 2;
  }
  ss_cli_fem_medium_args a = {
      .sigma_s_prime = sigma_s_prime,
      .sigma_a = sigma_a,
      .flakes = {.type = o->flakes,
                 .p = o->flake_p,
                 .axis = ss_vec3_make(o->axis[0], o->axis[1], o->axis[2])},
      .grid_path = o->grid_path,
      .grid_offset = {o->grid_offset[0], o->grid_offset[1], o->grid_offset[2]},
      .min_density = o->min_density};
  return ss_cli_fem_medium_init(med, &a);
}

/* The outward normal of the boundary face nearest to x (by its centroid);
 * *gap: that distance less the face's longest edge (> 0: x is off the
 * surface by at least that much). */
static ss_vec3 nearest_face_normal(const ss_fem_mesh *m, ss_vec3 x, double *gap) {
  double best = INFINITY;
  ss_vec3 n = ss_vec3_make(0, 0, 1);
  *gap = INFINITY;
  for (size_t f = 0; f < m->num_faces; ++f) {
    ss_vec3 p[3];
    ss_fem_face_vertices(m, f, p);
    ss_vec3 c = ss_vec3_scale(ss_vec3_add(ss_vec3_add(p[0], p[1]), p[2]), 1.0 / 3.0);
    double d = ss_vec3_length(ss_vec3_sub(c, x));
    if (d < best) {
      best = d;
      n = ss_vec3_normalize(ss_vec3_cross(ss_vec3_sub(p[1], p[0]), ss_vec3_sub(p[2], p[0])));
      double e = 0.0;
      for (int i = 0; i < 3; ++i) {
        e = fmax(e, ss_vec3_length(ss_vec3_sub(p[(i + 1) % 3], p[i])));
      }
      *gap = d - e;
    }
  }
  return n;
}

/* --size-medium: the grid's size field over [lo, hi] (or none). */
static ss_status medium_size(const options *o, double mfp, ss_cli_fem_medium *med, ss_vec3 lo,
                             ss_vec3 hi, ss_fem_size_field **field, ss_error *err) {
  *field = NULL;
  if (!(o->size_medium > 0.0)) {
    return SS_OK;
  }
  return ss_fem_scene_medium_size_field(
      &med->coeffs, lo, hi, fmin(o->size_medium, o->size_far) * mfp, o->size_far * mfp, field, err);
}

/* The tetrahedral mesh of the box or of the closed surface; 2 on bad input
 * (printed), 0 on success. */
static int make_mesh(options *o, double mfp, ss_cli_fem_medium *med, ss_fem_mesh **mesh) {
  ss_error err = {0};
  ss_fem_size_field *field = NULL;
  ss_fem_mesh_options mo = {.size_max = o->size_far * mfp,
                            .size_min = o->size_near * mfp,
                            .refine_center = ss_vec3_make(o->spot[0], o->spot[1], o->spot[2]),
                            .refine_radius = o->refine_radius,
                            .refine_grade = 4.0 * o->refine_radius,
                            .rim_radius = o->spot_radius,
                            .rim_size = o->rim_size * mfp};
  ss_status st;
  if (o->box_set) {
    ss_vec3 lo = ss_vec3_make(-0.5 * o->box[0], -0.5 * o->box[1], -o->box[2]),
            hi = ss_vec3_make(0.5 * o->box[0], 0.5 * o->box[1], 0.0);
    st = medium_size(o, mfp, med, lo, hi, &field, &err);
    mo.medium_size = field;
    if (st == SS_OK) {
      st = ss_fem_mesh_box(lo, hi, &mo, mesh, &err);
    }
  } else {
    ss_mesh *surf = NULL;
    st = ss_mesh_read(o->mesh_path, &surf, NULL, &err);
    if (st == SS_OK) {
      st = ss_mesh_check_closed(surf, &err);
      if (st != SS_OK) {
        ss_error_prefix(&err, "%s: not a closed surface: ", o->mesh_path);
      }
    }
    if (st == SS_OK && !o->spot_set) {
      ss_vec3 lo, hi;
      ss_mesh_bounds(surf, &lo, &hi);
      o->spot[0] = 0.5 * (lo.x + hi.x);
      o->spot[1] = 0.5 * (lo.y + hi.y);
      o->spot[2] = hi.z;
      mo.refine_center = ss_vec3_make(o->spot[0], o->spot[1], o->spot[2]);
    }
    if (st == SS_OK) {
      ss_vec3 lo, hi;
      ss_mesh_bounds(surf, &lo, &hi);
      st = medium_size(o, mfp, med, lo, hi, &field, &err);
      mo.medium_size = field;
    }
    if (st == SS_OK) {
      st = ss_fem_mesh_surface(surf->positions, surf->num_vertices, surf->indices,
                               surf->num_triangles, &mo, mesh, &err);
      if (st != SS_OK) {
        drop_library_prefix(&err);
        ss_error_prefix(&err, "%s: ", o->mesh_path);
      }
    }
    ss_mesh_destroy(surf);
  }
  ss_fem_size_field_destroy(field);
  if (st != SS_OK) {
    print_error(&err);
    return st == SS_ERR_NO_MEMORY ? 1 : 2;
  }
  return 0;
}

static cJSON *summary_json(const options *o, const ss_fem_mesh *m, const ss_fem_solution *s,
                           double mesh_seconds, double h) {
  cJSON *root = cJSON_CreateObject();
  cJSON_AddStringToObject(root, "command", CMD);
  cJSON_AddStringToObject(root, "solver", o->solve.solver == SS_FEM_CHOLMOD ? "cholmod" : "pcg");
  cJSON_AddNumberToObject(root, "vertices", (double)m->num_vertices);
  cJSON_AddNumberToObject(root, "tetrahedra", (double)m->num_tets);
  cJSON_AddNumberToObject(root, "boundary_triangles", (double)m->num_faces);
  cJSON_AddNumberToObject(root, "max_edge", h);
  cJSON_AddNumberToObject(root, "nonzeros", (double)s->nonzeros);
  cJSON_AddNumberToObject(root, "iterations", s->iterations);
  cJSON_AddNumberToObject(root, "residual", s->residual);
  cJSON_AddNumberToObject(root, "mesh_seconds", mesh_seconds);
  cJSON_AddNumberToObject(root, "assemble_seconds", s->assemble_seconds);
  cJSON_AddNumberToObject(root, "solve_seconds", s->solve_seconds);
  cJSON_AddNumberToObject(root, "injected", s->injected);
  cJSON_AddNumberToObject(root, "absorbed", s->absorbed);
  cJSON_AddNumberToObject(root, "escaped", s->escaped);
  if (o->n_profile > 0) {
    cJSON *prof = cJSON_AddArrayToObject(root, "profile");
    for (int i = 0; i < o->n_profile; ++i) {
      double v = 0.0;
      int inside = ss_fem_interpolate(
          m, s->exitance, ss_vec3_make(o->spot[0] + o->profile_r[i], o->spot[1], o->spot[2]), &v);
      cJSON *p = cJSON_CreateObject();
      cJSON_AddNumberToObject(p, "r", o->profile_r[i]);
      if (inside) {
        cJSON_AddNumberToObject(p, "exitance", v);
      } else {
        cJSON_AddNullToObject(p, "exitance");
      }
      cJSON_AddItemToArray(prof, p);
    }
  }
  return root;
}

static int run(options *o) {
  double sigma_s_prime = (1.0 - o->g) * o->sigma_s, sigma_a = o->sigma_a;
  if (o->preset) {
    sigma_s_prime = o->preset->sigma_s_prime[o->channel];
    sigma_a = o->preset->sigma_a[o->channel];
    o->eta = o->eta_set ? o->eta : o->preset->eta;
  }
  sigma_s_prime *= o->scale;
  sigma_a *= o->scale;
  double st = sigma_s_prime + sigma_a;
  if (!(sigma_s_prime > 0.0)) {
    fprintf(stderr, "subsurf " CMD ": the reduced scattering coefficient must be > 0\n");
    return 2;
  }
  ss_cli_fem_medium med;
  int rc = make_medium(o, sigma_s_prime, sigma_a, &med);
  if (rc) {
    return rc;
  }
  /* the shortest transport mean free path: at the grid's largest density */
  double mfp = 1.0 / (st * ss_cli_fem_medium_max_density(&med));
  o->spot_radius = (o->spot_radius_set ? o->spot_radius : 0.5) * mfp;
  o->refine_radius = o->refine_radius_set ? o->refine_radius * mfp : o->spot_radius + mfp;
  double t0 = ss_seconds();
  ss_fem_mesh *mesh = NULL;
  rc = make_mesh(o, mfp, &med, &mesh);
  if (rc) {
    ss_cli_fem_medium_release(&med);
    return rc;
  }
  double mesh_seconds = ss_seconds() - t0;
  ss_vec3 c = ss_vec3_make(o->spot[0], o->spot[1], o->spot[2]);
  ss_fem_problem pb = {.eta = o->eta};
  ss_error err = {0};
  ss_status s = SS_OK;
  ss_fem_ray *rays = NULL;
  if (o->point_source) {
    /* the classical dipole's source (Jensen et al. 2001, sec. 2.1) */
    pb.point = ss_vec3_add(c, ss_vec3_make(0, 0, -mfp));
    pb.point_power = o->spot_power * sigma_s_prime / st;
  } else if (o->boundary_source) {
    /* Jakob2010 eq. 37: the refracted power attenuated by exp(-sigma_a/sigma_s) */
    pb.spot_center = c;
    pb.spot_radius = o->spot_radius;
    pb.spot_power = o->spot_power * exp(-sigma_a / sigma_s_prime);
  } else {
    /* the first scattering events along the refracted rays of the diffuse
     * spot (fem_rays.c): extinction and albedo of the first event along
     * each ray from the medium just below the spot (sigma_t' and alpha', or
     * the flakes' reduced by the similarity relation: fem_medium.h), power P
     * times that albedo */
    double gap;
    ss_vec3 n = nearest_face_normal(mesh, c, &gap);
    ss_fem_scene_sigma_at at = {&med.coeffs, ss_vec3_sub(c, ss_vec3_scale(n, 1e-6 * mfp))};
    s = gap > o->spot_radius
            ? ss_error_set(&err, SS_ERR_INVALID_ARGUMENT,
                           "the spot (centre %g %g %g, radius %g) does not touch the boundary", c.x,
                           c.y, c.z, o->spot_radius)
            : ss_fem_spot_rays(c, n, o->spot_radius, o->spot_power, 1, 6, 6, ss_fem_scene_sigma_fn,
                               &at, &rays, &pb.num_rays, &err);
    for (size_t i = 0; s == SS_OK && i < pb.num_rays; ++i) {
      rays[i].power *= ss_fem_scene_medium_first_event(&med.coeffs, at.at, rays[i].dir).albedo;
    }
    pb.rays = rays;
  }
  ss_fem_solution *sol = NULL;
  if (s == SS_OK) {
    s = ss_fem_solve(mesh, ss_fem_scene_medium_at, &med.coeffs, &pb, &o->solve, &sol, &err);
  }
  free(rays);
  ss_cli_fem_medium_release(&med);
  if (s != SS_OK) {
    print_error(&err);
    ss_fem_mesh_destroy(mesh);
    return s == SS_ERR_INVALID_ARGUMENT ? 2 : 1;
  }
  cJSON *json = summary_json(o, mesh, sol, mesh_seconds, ss_fem_mesh_max_edge(mesh));
  rc = 0;
  output_paths[0] = o->output;
  output_paths[1] = o->json_path && strcmp(o->json_path, "-") ? o->json_path : NULL;
  writing = 1;
  if (ss_fem_write_ply(o->output, mesh, sol, &err) != SS_OK) {
    print_error(&err);
    rc = 1;
  } else if (o->json_path && ss_json_write_file(json, o->json_path, CMD) != 0) {
    remove(o->output); /* all outputs or none */
    rc = 1;
  }
  signal(SIGINT, SIG_IGN); /* written (or removed): a late signal changes nothing */
  signal(SIGTERM, SIG_IGN);
  if (rc == 0 && !o->json_path) {
    printf("fem: %zu vertices, %zu tetrahedra, %zu boundary triangles (max edge %.4g)\n",
           mesh->num_vertices, mesh->num_tets, mesh->num_faces, ss_fem_mesh_max_edge(mesh));
    printf("  mesh %.3f s, assemble %.3f s CPU, solve (%s) %.3f s CPU, residual %.2e\n",
           mesh_seconds, sol->assemble_seconds,
           o->solve.solver == SS_FEM_CHOLMOD ? "cholmod" : "pcg", sol->solve_seconds,
           sol->residual);
    printf("  injected %.6g, absorbed %.6g, escaped %.6g\n", sol->injected, sol->absorbed,
           sol->escaped);
    printf("  wrote %s\n", o->output);
  }
  cJSON_Delete(json);
  ss_fem_solution_destroy(sol);
  ss_fem_mesh_destroy(mesh);
  return rc;
}

int ss_cmd_fem(int argc, char **argv) {
  options o = {.sigma_s = 1.0,
               .sigma_a = 0.01,
               .eta = 1.3,
               .scale = 1.0,
               .spot_power = 1.0,
               .flake_p = 20.0,
               .axis = {0, 0, 1},
               .size_near = 0.25,
               .size_far = 2.0,
               .min_density = 0.01,
               .solve = {.solver = SS_FEM_CHOLMOD, .tolerance = 1e-8, .max_iterations = 100000}};
  exit_on_interrupt();
  int rc = parse_args(&o, argc, argv);
  if (rc != 0) {
    return rc == 1 ? 0 : rc;
  }
  return run(&o);
}
