/* Model options by name: every declaration in the registry is well formed,
 * values are parsed and range-checked with messages naming the model and the
 * option, and the typed getters return what was set or the default. */
#include "subsurf/bssrdf.h"
#include "subsurf/bssrdf_layers.h"

#include <criterion/criterion.h>
#include <ctype.h>
#include <math.h>
#include <string.h>

Test(bssrdf_options, every_declared_option_is_snake_case_with_help_and_a_valid_default) {
  for (size_t m = 0; m < ss_bssrdf_model_count(); ++m) {
    const ss_bssrdf_ops *ops = ss_bssrdf_model_at(m);
    cr_assert(ss_bssrdf_option_count(ops) <= SS_BSSRDF_MAX_OPTIONS, "%s", ops->name);
    for (size_t k = 0; k < ss_bssrdf_option_count(ops); ++k) {
      const ss_option *o = &ops->options[k];
      for (const char *c = o->name; *c; ++c) {
        cr_expect(islower((unsigned char)*c) || *c == '_', "%s: option '%s'", ops->name, o->name);
      }
      cr_expect(o->help && o->help[0], "%s: option %s has no help", ops->name, o->name);
      cr_expect(o->type != SS_OPTION_CHOICE || o->choices, "%s", o->name);
      ss_bssrdf_params p;
      ss_bssrdf_params_default(&p);
      ss_error err;
      cr_expect_eq(ss_bssrdf_params_set_option(&p, ops, o->name, o->def, &err), SS_OK,
                   "%s: the default of %s: %s", ops->name, o->name, err.message);
      cr_expect_eq(ss_bssrdf_option_find(ops, o->name), o);
    }
  }
}

Test(bssrdf_options, unknown_option_names_the_model_and_its_options) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_error err;
  const ss_bssrdf_ops *pbd = ss_bssrdf_model_find("pbd");
  cr_assert_eq(ss_bssrdf_params_set_option(&p, pbd, "thicknes", "1", &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "pbd: unknown option 'thicknes' (options: beam_samples, tabulate)"),
            "%s", err.message);
  cr_expect_eq(p.n_options, 0);
}

Test(bssrdf_options, out_of_range_and_malformed_values_name_model_option_and_range) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_error err;
  const ss_bssrdf_ops *pbd = ss_bssrdf_model_find("pbd");
  cr_assert_eq(ss_bssrdf_params_set_option(&p, pbd, "beam_samples", "3", &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "pbd: option beam_samples: expected a whole number in [6, 384], "
                                "got '3'"),
            "%s", err.message);
  const char *bad[] = {"", "12x", "1.5", "nan", "385"};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    cr_expect_eq(ss_bssrdf_params_set_option(&p, pbd, "beam_samples", bad[i], &err),
                 SS_ERR_INVALID_ARGUMENT, "'%s'", bad[i]);
  }
  cr_expect_eq(ss_bssrdf_params_set_option_number(&p, pbd, "beam_samples", 50.5, &err),
               SS_ERR_INVALID_ARGUMENT);
  const ss_bssrdf_ops *mp = ss_bssrdf_model_find("multipole");
  cr_expect_eq(ss_bssrdf_params_set_option(&p, mp, "thickness", "0", &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "in (0, inf]"), "%s", err.message);
  cr_expect_eq(ss_bssrdf_params_set_option(&p, mp, "thickness", "inf", &err), SS_OK);
  const ss_bssrdf_ops *dp = ss_bssrdf_model_find("dipole");
  cr_expect_eq(ss_bssrdf_params_set_option(&p, dp, "min_distance", "maybe", &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "dipole: option min_distance: expected true or false"), "%s",
            err.message);
}

Test(bssrdf_options, getters_return_the_value_set_last_or_the_default) {
  const ss_bssrdf_ops *pbd = ss_bssrdf_model_find("pbd");
  const ss_option *o = ss_bssrdf_option_find(pbd, "beam_samples");
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  cr_expect_eq(ss_bssrdf_params_int(&p, o), 100);
  cr_assert_eq(ss_bssrdf_params_set_option(&p, pbd, "beam_samples", "30", NULL), SS_OK);
  cr_assert_eq(ss_bssrdf_params_set_option_number(&p, pbd, "beam_samples", 60, NULL), SS_OK);
  cr_expect_eq(ss_bssrdf_params_int(&p, o), 60);
  cr_expect_eq(p.n_options, 1);
  const ss_bssrdf_ops *mp = ss_bssrdf_model_find("multipole");
  const ss_option *t = ss_bssrdf_option_find(mp, "thickness");
  cr_expect(isinf(ss_bssrdf_params_double(&p, t)));
  const ss_bssrdf_ops *gwc = ss_bssrdf_model_find("table-gwc");
  const ss_option *table = ss_bssrdf_option_find(gwc, "table");
  cr_expect_str_eq(ss_bssrdf_params_string(&p, table), "");
  cr_assert_eq(ss_bssrdf_params_set_option(&p, gwc, "table", "a b.sstab", NULL), SS_OK);
  cr_expect_str_eq(ss_bssrdf_params_string(&p, table), "a b.sstab");
  const ss_option *md = ss_bssrdf_option_find(ss_bssrdf_model_find("dipole"), "min_distance");
  cr_expect_eq(ss_bssrdf_params_bool(&p, md), 0);
  ss_bssrdf_params_clear_options(&p);
  cr_expect_eq(ss_bssrdf_params_int(&p, o), 100);
}

/* An option set for one model is an error for a model that does not declare
 * it, rather than silently ignored. */
Test(bssrdf_options, create_refuses_an_option_the_model_does_not_declare) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  cr_assert_eq(
      ss_bssrdf_params_set_option(&p, ss_bssrdf_model_find("pbd"), "beam_samples", "30", NULL),
      SS_OK);
  ss_bssrdf *b = NULL;
  ss_error err;
  cr_expect_eq(ss_bssrdf_create("dipole", &p, &b, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "dipole: unknown option 'beam_samples'"), "%s", err.message);
  cr_expect_eq(b, NULL);
  cr_assert_eq(ss_bssrdf_create("pbd", &p, &b, &err), SS_OK, "%s", err.message);
  ss_bssrdf_destroy(b);
}

Test(bssrdf_options, describe_gives_kind_range_and_default) {
  char buf[256];
  ss_bssrdf_option_describe(ss_bssrdf_option_find(ss_bssrdf_model_find("pbd"), "beam_samples"), buf,
                            sizeof buf);
  cr_expect_str_eq(buf, "a whole number in [6, 384], default 100");
  ss_bssrdf_option_describe(ss_bssrdf_option_find(ss_bssrdf_model_find("table-gwc"), "table"), buf,
                            sizeof buf);
  cr_expect_str_eq(buf, "text, default none");
  ss_bssrdf_option_names(ss_bssrdf_model_find("single"), buf, sizeof buf);
  cr_expect_str_eq(buf, "none");
}

Test(bssrdf_layers, a_formatted_stack_parses_back_exactly) {
  ss_bssrdf_layer_stack s;
  ss_error err;
  cr_assert_eq(ss_bssrdf_layer_stack_parse("skin", &s, &err), SS_OK);
  cr_assert_eq(s.layer_count, 3);
  cr_expect(isinf(s.layers[2].thickness));
  char text[SS_OPTION_TEXT];
  int n = ss_bssrdf_layer_stack_format(&s, text, sizeof text);
  cr_assert(n > 0 && n < (int)sizeof text);
  cr_expect_eq(ss_bssrdf_layer_stack_format(&s, NULL, 0), n);
  ss_bssrdf_layer_stack back;
  cr_assert_eq(ss_bssrdf_layer_stack_parse(text, &back, &err), SS_OK, "%s", err.message);
  cr_expect_eq(memcmp(&s, &back, sizeof s), 0);
}

Test(bssrdf_layers, gray_values_and_default_g_fill_all_channels) {
  ss_bssrdf_layer_stack s;
  ss_error err;
  cr_assert_eq(ss_bssrdf_layer_stack_parse("sigma_s=2 sigma_a=0.1,0.2,0.3 eta=1.3 d=inf", &s, &err),
               SS_OK, "%s", err.message);
  cr_expect_eq(s.layer_count, 1);
  cr_expect_eq(s.layers[0].sigma_s[2], 2.0);
  cr_expect_eq(s.layers[0].sigma_a[1], 0.2);
  cr_expect_eq(s.layers[0].g[0], 0.0);
}

Test(bssrdf_layers, malformed_stacks_name_the_layer_and_key) {
  const char *bad[][2] = {
      {"sigma_s=1 sigma_a=0.1 eta=1.3 d=1; sigma_s=1 sigma_a=0.1 eta=1.3", "layer 1: missing d="},
      {"sigma_s=1,2 sigma_a=0.1 eta=1.3 d=1", "layer 0: sigma_s"},
      {"sigma_s=1 sigma_a=0.1 eta=1.3,1.4,1.5 d=1", "layer 0: eta: expected a number"},
      {"sigma_s=1 sigma_a=0.1 eta=1.3 d=1 colour=red", "layer 0: expected sigma_s="},
      {"", "expected 'skin'"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    ss_bssrdf_layer_stack s;
    ss_error err;
    cr_expect_eq(ss_bssrdf_layer_stack_parse(bad[i][0], &s, &err), SS_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(err.message, bad[i][1]), "'%s': %s", bad[i][0], err.message);
  }
}
