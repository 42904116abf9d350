/* The numbers of the half-space reference's parameters as text (halfspace.h). */
#include "subsurf/halfspace.h"
#include "subsurf/threads.h"

const ss_arg ss_halfspace_args[] = {
    {"sigma-s", SS_ARG_NUMBER, 0, 0},
    {"sigma-a", SS_ARG_NUMBER, 0, 0},
    {"g", SS_ARG_NUMBER, 0, 0},
    {"eta", SS_ARG_NUMBER, 0, 0},
    {"theta-i", SS_ARG_NUMBER, 0, 0},
    {"thickness", SS_ARG_NUMBER_OR_INF, 0, 0},
    {"paths", SS_ARG_WHOLE, 1, SS_ARG_U64_END},
    {"time-limit", SS_ARG_NUMBER, 0, 0},
    {"seed", SS_ARG_WHOLE, 0, SS_ARG_U64_END},
    SS_THREADS_ARG,
    {"max-depth", SS_ARG_WHOLE, 1, SS_ARG_U64_END},
    {"rmin", SS_ARG_NUMBER, 0, 0},
    {"rmax", SS_ARG_NUMBER, 0, 0},
    {"rbins", SS_ARG_WHOLE, 2, SS_HALFSPACE_MAX_BINS},
    {"theta-o", SS_ARG_NUMBER, 0, 0},
    {"xmin", SS_ARG_NUMBER, 0, 0},
    {"xmax", SS_ARG_NUMBER, 0, 0},
    {"xbins", SS_ARG_WHOLE, 1, SS_HALFSPACE_MAX_BINS},
    {"ymin", SS_ARG_NUMBER, 0, 0},
    {"ymax", SS_ARG_NUMBER, 0, 0},
    {"ybins", SS_ARG_WHOLE, 1, SS_HALFSPACE_MAX_BINS},
    {NULL, SS_ARG_NUMBER, 0, 0},
};
