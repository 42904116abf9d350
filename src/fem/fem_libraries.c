/* The gmsh and CHOLMOD the fem module loads (fem.h, ss_fem_libraries). */
#include "subsurf/fem.h"

#include <cholmod.h>
#include <gmshc.h>

#define SS_STR(x) #x
#define SS_XSTR(x) SS_STR(x)
#define SS_CHOLMOD_VERSION                                                                         \
  SS_XSTR(CHOLMOD_MAIN_VERSION) "." SS_XSTR(CHOLMOD_SUB_VERSION) "." SS_XSTR(CHOLMOD_SUBSUB_VERSION)

const char *ss_fem_libraries(void) {
  return "gmsh " GMSH_API_VERSION " (" SUBSURF_GMSH_LIBRARY "), CHOLMOD " SS_CHOLMOD_VERSION
         " (" SUBSURF_CHOLMOD_LIBRARY ")";
}
