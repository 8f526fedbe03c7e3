/*
 * Internal: numbers as the query protocol writes and reads them
 * (docs/PROTOCOL.md, "Numbers"), exactly as the C library does and at a
 * fraction of its cost. glibc's printf and strtod take multi-precision
 * arithmetic for every number; a query line is six numbers and its answer
 * four or eight, and with the C library those conversions were about 70%
 * of materia-query's time and half of the suite's own through the protocol.
 * Both functions give the ordinary cases to integer and exact floating
 * arithmetic and every other case to the C library, so the text is the
 * same byte for byte and the values bit for bit.
 */
#ifndef MT_CORE_NUMTEXT_H
#define MT_CORE_NUMTEXT_H

#include <stddef.h>

/* printf's "%.9g" of (double)f, the same characters, into out (size bytes,
 * at least 24 for the fast path); the length. Nine digits read back to f. */
int mt__format_g9(char *out, size_t size, float f);

/* v as a C99 hexadecimal float ("0x1.8p-3", "-0x0p+0"), exact, the fewest
 * hexadecimal digits, into out (at least 32 bytes); the length. What strtod
 * (and Python's float.fromhex) reads back to v, bit for bit. NaN and
 * infinities are printf's "%a". */
int mt__format_hex(char *out, size_t size, double v);

/* strtod(s, end), the same double and the same end for every input: a
 * decimal of at most 15 significant digits and a power of ten up to 22
 * (every number the suite and materia-query write in float) is one exact
 * multiplication or division (Clinger's fast path, correctly rounded);
 * anything else (inf, nan, a leading space or '+', more
 * digits, a larger exponent) is strtod's. A hexadecimal float of at most
 * 53 significant bits and a normal result ("0x1.8p-3") is read exactly
 * here too. */
double mt__strtod(const char *s, char **end);

#endif
