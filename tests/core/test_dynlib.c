/* Opening a shared object and its symbols at run time (core/dynlib.h): the
 * addresses of what it defines, or one message saying why it cannot be used,
 * with nothing half-loaded. libm stands in for gmsh, CHOLMOD and the
 * plugins. */
#include "core/dynlib.h"

#include <criterion/criterion.h>
#include <string.h>

typedef double unary_fn(double);

Test(dynlib, the_symbols_of_a_library_are_stored_where_asked) {
  unary_fn *c = NULL, *s = NULL;
  const ss_dynlib_symbol symbols[] = {{"cos", (void **)&c}, {"sqrt", (void **)&s}};
  ss_error err;
  cr_assert_eq(ss_dynlib_open("libm.so.6", "libm", "install libc6", "libm", symbols, 2, &err),
               SS_OK, "%s", err.message);
  cr_assert(c && s);
  cr_expect_eq(c(0.0), 1.0);
  cr_expect_eq(s(16.0), 4.0);
}

Test(dynlib, a_missing_symbol_is_named_and_no_address_is_left) {
  unary_fn *c = NULL;
  void *missing = &c;
  const ss_dynlib_symbol symbols[] = {{"cos", (void **)&c}, {"ss_no_such_symbol", &missing}};
  ss_error err;
  cr_assert_eq(
      ss_dynlib_open("libm.so.6", "libm", "install libc6", "glibc's libm", symbols, 2, &err),
      SS_ERR_UNSUPPORTED);
  cr_expect_str_eq(err.message, "libm.so.6 has no ss_no_such_symbol (glibc's libm expected)");
  cr_expect_null(c, "cos, found before the missing symbol, was kept");
  cr_expect_null(missing);
}

Test(dynlib, a_library_that_does_not_load_is_named_with_the_remedy) {
  void *f = &f;
  const ss_dynlib_symbol symbol = {"f", &f};
  ss_error err;
  const char *path = "/nonexistent/libsubsurf_nothing.so";
  cr_assert_eq(ss_dynlib_open(path, "Nothing", "install libnothing-dev (scripts/install-deps.sh)",
                              "Nothing 1", &symbol, 1, &err),
               SS_ERR_UNSUPPORTED);
  const char *head = "cannot load Nothing (/nonexistent/libsubsurf_nothing.so): ";
  const char *tail = "; install libnothing-dev (scripts/install-deps.sh)";
  size_t n = strlen(err.message);
  cr_expect(!strncmp(err.message, head, strlen(head)), "%s", err.message);
  cr_expect(strstr(err.message, "No such file"), "dlerror's reason: %s", err.message);
  cr_expect(n > strlen(tail) && !strcmp(err.message + n - strlen(tail), tail), "%s", err.message);
  cr_expect_null(f);
}
