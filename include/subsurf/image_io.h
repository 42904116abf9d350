/* Image files: OpenEXR (linear float, through the OpenEXR Core C API), PNG
 * (exposure, then sRGB-encoded 8 bit, through stb_image_write) and PFM.
 * Every writer writes to a temporary file beside the target and renames it on
 * success, so a failed or interrupted write never leaves a file that looks
 * complete. 1-channel images are written as Y (EXR) or grey (PNG/PFM);
 * 3-channel ones as RGB; 4-channel ones as RGBA. */
#ifndef SUBSURF_IMAGE_IO_H
#define SUBSURF_IMAGE_IO_H

#include "subsurf/image.h"
#include "subsurf/status.h"

/* IEC 61966-2-1 (sRGB) encoding of a linear value in [0, 1], as PNGs are
 * written. */
double ss_srgb_encode(double v);

ss_status ss_image_write_exr(const char *path, const ss_image *img, ss_error *err);
/* PNG: value * 2^exposure, clamped, sRGB transfer curve. */
ss_status ss_image_write_png(const char *path, const ss_image *img, double exposure, ss_error *err);
ss_status ss_image_write_pfm(const char *path, const ss_image *img, ss_error *err);
/* Picks the format from the extension (.exr, .png, .pfm); anything else is an
 * SS_ERR_INVALID_ARGUMENT naming the path. */
ss_status ss_image_write(const char *path, const ss_image *img, double exposure, ss_error *err);
/* 1 when the extension is one of the above. */
int ss_image_format_supported(const char *path);

/* Reads an EXR, PFM or PNG (told by its first bytes; a PNG's sRGB codes
 * decoded to linear values, without the exposure it was written with) for
 * tests, comparing images and the Python module; the caller destroys the
 * image. */
ss_status ss_image_read(const char *path, ss_image **out, ss_error *err);

#endif
