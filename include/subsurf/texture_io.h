/* Reading texture images: PNG through stb_image (8 or 16 bit), Radiance
 * HDR (.hdr, RGBE) through stb_image, EXR through the OpenEXR Core C API,
 * decoded to linear float.
 *
 * PNG values are sRGB-encoded colours when `srgb` is set (IEC 61966-2-1
 * decoding, what colour maps hold) and plain data otherwise (roughness
 * maps: v / 255 or v / 65535). EXR and HDR are linear and read as they are. The image
 * gets 1 channel (grey) or 3 (RGB); alpha is dropped. Errors name the path. */
#ifndef SUBSURF_TEXTURE_IO_H
#define SUBSURF_TEXTURE_IO_H

#include "subsurf/image.h"
#include "subsurf/status.h"

/* Width and height of a texture image are at most this many texels. */
#define SS_TEXTURE_MAX_SIZE 32768

ss_status ss_texture_image_read(const char *path, int srgb, ss_image **out, ss_error *err);

/* IEC 61966-2-1: the linear value of an sRGB-encoded one, both in [0, 1]. */
double ss_srgb_decode(double v);

#endif
