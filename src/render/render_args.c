/* The numbers of a render's options as text (render.h). */
#include "subsurf/render.h"
#include "subsurf/threads.h"

const ss_arg ss_render_args[] = {
    {"spp", SS_ARG_WHOLE, 1, SS_RENDER_MAX_SPP},
    SS_THREADS_ARG,
    {"seed", SS_ARG_WHOLE, 0, SS_ARG_U64_END},
    {NULL, SS_ARG_NUMBER, 0, 0},
};
