/* decimal.h: reading a number as strtod does in the C locale, faster for
 * the short decimals scene files are made of. */
#ifndef TP2_DECIMAL_H
#define TP2_DECIMAL_H

/* The same value and end as strtod(s, end) in the C locale, bit for bit.
 * Decimals of at most 19 significant digits whose value is m * 10^e with
 * m <= 2^53 and |e| <= 22 are converted with one IEEE multiplication or
 * division of two exact doubles (Clinger's fast path), which rounds once,
 * to nearest, exactly as strtod must; anything else goes to strtod. */
double decimal_read(const char *s, char **end);

#endif
