/* The one grammar for numbers written by people (command-line options, model
 * options, option texts such as the layers stack):
 *   [+-] digits [. digits] [(e|E) [+-] digits]   (or [+-] . digits ...)
 * with nothing before or after it: no spaces, no hexadecimal, no "inf" or
 * "nan", no empty text. The value must be finite in double precision (1e309
 * is refused); values too small for a normal double (1e-320) read as
 * themselves, and -0 reads as 0. */
#ifndef SUBSURF_NUMBER_H
#define SUBSURF_NUMBER_H

/* 1 when `text` is a number of the grammar above (stored in *out), else 0. */
int ss_number_parse(const char *text, double *out);

/* The same for the first `len` characters of `text` (a field of a list). */
int ss_number_parse_n(const char *text, unsigned long len, double *out);

/* `v` for a message: a whole number below 2^63 in magnitude in full
 * ("100000000", never "1e+08"), any other value as %g. */
void ss_number_format(double v, char *buf, unsigned long size);

#endif
