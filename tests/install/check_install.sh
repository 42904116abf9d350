#!/usr/bin/env bash
# make install, as a user would use it: install the build into a
# temporary prefix, build a tiny C program against the installed copy with
# pkg-config alone, run it, import the installed Python module without any
# hint of where the build is, and run the installed CLI.
# usage: check_install.sh BUILD_DIR
set -euo pipefail
build=$1
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" >/dev/null

export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
version=$(sed -n 's/^project(subsurf VERSION \([0-9.]*\).*/\1/p' "$(dirname "$0")/../../CMakeLists.txt")
if [ "$(pkg-config --modversion subsurf)" != "$version" ]; then
  echo "check_install: pkg-config says $(pkg-config --modversion subsurf), CMakeLists.txt $version" >&2
  exit 1
fi
cat >"$prefix/tiny.c" <<'C'
#include <subsurf/bssrdf.h>
#include <stdio.h>

int main(void) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf *b;
  ss_error err;
  if (ss_bssrdf_create("dipole", &p, &b, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  double rd[3];
  ss_bssrdf_total_reflectance(b, 1.0, rd);
  printf("%.6f\n", rd[0]);
  ss_bssrdf_destroy(b);
  return 0;
}
C
# shellcheck disable=SC2046
cc -std=c11 -Wall -Werror -o "$prefix/tiny" "$prefix/tiny.c" $(pkg-config --cflags --libs subsurf)
rd=$(LD_LIBRARY_PATH="$prefix/lib" "$prefix/tiny")
awk -v r="$rd" 'BEGIN { exit !(r > 0 && r < 1) }'

# The prefix is laid out as a user site: python3 finds the module through
# PYTHONUSERBASE alone, as it finds PREFIX=$HOME/.local with no setting.
py=$(env -u SUBSURF_LIB -u SUBSURF_BIN -u PYTHONPATH PYTHONUSERBASE="$prefix" /usr/bin/python3 -c '
import subsurf
with subsurf.Model("dipole", subsurf.Medium(1.0, 0.01, 0.0, 1.3)) as m:
    print("%.6f" % m.total_reflectance()[0], subsurf._lib.binary())')
test "${py%% *}" = "$rd"
test "${py#* }" = "$prefix/bin/subsurf"
"$prefix/bin/subsurf" --help >/dev/null
echo "installed into a temporary prefix: C via pkg-config and Python agree (R_d = $rd)"
