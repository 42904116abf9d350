/* `hierarchical`: the hierarchical BSSRDF evaluation of
 * JensenBuhler2002 (sec. 3). Pass 1 (prepare, hierarchical_build.c)
 * spreads blue-noise points over every translucent object, computes the
 * Fresnel-transmitted irradiance at each with the `bssrdf` integrator's
 * lighting and builds one octree per object. Pass 2 is path tracing of the
 * surfaces as in `bssrdf` (diffusion_path.c), except at a translucent surface seen from outside
 * at x_o toward w_o: there the diffusion term
 *     L_d(x_o, w_o) = sum_j K(x_j; x_o, w_o) E_j A_j
 * (K the material's radially symmetric model, hierarchical.h) is evaluated
 * from the octree with the solid-angle criterion epsilon (through the
 * tabulated kernel of hierarchical_table.c where the build kept one), the single
 * scattering term of Jensen et al. 2001 added for "single_scattering"
 * materials, and the path continues by the boundary's reflection lobe only
 * (no branch: both terms are taken every time). */
#include "render/integrators/hierarchical.h"
#include "render/integrators/common.h"
#include "render/integrators/diffusion_path.h"

#include <math.h>
#include <string.h>

void ss_hier_kernel(const void *ctx, ss_vec3 x_i, ss_vec3 n_i, double k[3]) {
  const ss_hier_kernel_ctx *c = ctx;
  ss_bssrdf_query q = {x_i, n_i, n_i, c->x_o, c->n_o, c->w_o, 0.0};
  ss_bssrdf_eval(c->b, &q, k);
  for (int i = 0; i < 3; ++i) {
    k[i] *= c->inv_ft_normal;
  }
}

static ss_status hier_check(const ss_scene *scene, ss_error *err) {
  ss_hier_options o;
  ss_status st = ss_refuse_nested_media(scene, "hierarchical", err);
  if (st == SS_OK) {
    st = ss_refuse_varying_media(scene, "hierarchical",
                                 "one kernel per shape; use the bssrdf integrator", err);
  }
  return st == SS_OK ? ss_hier_options_read(scene, &o, err) : st;
}

static ss_status hier_prepare(const ss_scene *scene, void **state, ss_error *err) {
  ss_hier_options o;
  ss_status st = hier_check(scene, err);
  if (st == SS_OK) {
    st = ss_subsurface_build(scene->subsurface, err);
  }
  if (st != SS_OK || (st = ss_hier_options_read(scene, &o, err)) != SS_OK) {
    return st;
  }
  ss_hier_state *s = NULL;
  st = ss_hier_build(scene, &o, 0, scene->integrator.cache, &s, err);
  *state = s;
  return st;
}

static void hier_release(void *state) { ss_hier_destroy(state); }

ss_rgb ss_hier_sum_near(const ss_irradiance_octree *t, ss_vec3 n_o, double epsilon, double r,
                        const double disk[3], const ss_hier_table_ctx *tk, uint64_t *evals) {
  ss_octree_near near = {.r2 = r * r, .n = n_o};
  ss_rgb m = ss_irradiance_octree_sum_near(t, tk->x_o, epsilon, ss_hier_kernel_tabulated, tk, &near,
                                           evals);
  for (int c = 0; c < 3; ++c) {
    double mass = tk->a[c] * disk[c];
    m.c[c] +=
        near.flat && near.weight[c] > 0.0 ? near.sum.c[c] * (mass / near.weight[c]) : near.sum.c[c];
  }
  return m;
}

/* The diffusion term at the exit point `hit` seen along d. */
static ss_rgb diffusion(const void *state, const ss_hit *hit, ss_vec3 d, ss_path_stats *stats) {
  const ss_hier_state *s = state;
  if (hit->geom_id >= s->num_shapes || !s->kernel[hit->geom_id]) {
    return ss_rgb_gray(0.0);
  }
  const ss_irradiance_octree *t = &s->trees[hit->geom_id];
  ss_hier_kernel_ctx k = {.b = s->kernel[hit->geom_id],
                          .x_o = hit->p,
                          .n_o = hit->ng,
                          .w_o = ss_vec3_neg(d),
                          .inv_ft_normal =
                              1.0 / ss_irradiance_fresnel_weight(1.0, s->eta[hit->geom_id])};
  uint64_t evals = 0;
  const ss_hier_table *table = &s->table[hit->geom_id];
  if (table->n) {
    ss_hier_table_ctx tk = {.table = table, .x_o = hit->p};
    ss_hier_table_angular(table, &k, tk.a);
    double r = s->near_radius[hit->geom_id];
    if (r > 0.0) {
      ss_rgb m =
          ss_hier_sum_near(t, hit->ng, s->opt.epsilon, r, s->near_disk[hit->geom_id], &tk, &evals);
      stats->probe_rays += evals;
      return m;
    }
    ss_rgb m =
        ss_irradiance_octree_sum(t, hit->p, s->opt.epsilon, ss_hier_kernel_tabulated, &tk, &evals);
    stats->probe_rays += evals;
    return m;
  }
  ss_rgb m = ss_irradiance_octree_sum(t, hit->p, s->opt.epsilon, ss_hier_kernel, &k, &evals);
  stats->probe_rays += evals; /* counted as the term's work: kernel evaluations */
  return m;
}

static ss_rgb hier_li(const ss_scene *scene, const void *state, ss_ray ray, ss_rng *rng,
                      ss_path_stats *stats) {
  return ss_diffusion_path_li(scene, diffusion, state, ray, rng, stats);
}

static const char *const hier_options[] = {"points",       "epsilon",    "irradiance_samples",
                                           "kernel_table", "near_field", NULL};

const ss_integrator_ops ss_integrator_hierarchical = {
    .name = "hierarchical",
    .summary = "BSSRDF diffusion from an octree of irradiance points on the translucent surfaces "
               "(Jensen & Buhler 2002)",
    .options = hier_options,
    .check = hier_check,
    .prepare = hier_prepare,
    .release = hier_release,
    .li = hier_li,
};
