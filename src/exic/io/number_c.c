/* The C side of exic_io_number (src/exic/io/number.f90): one real as the text of Fortran's
 * `1x,es24.16e3` edit descriptor, for the rows of <stem>.his and <stem>.ene.
 *
 * snprintf's "%.16e" gives the 17 significant digits correctly rounded from the exact binary
 * value (glibc), as libgfortran's ES editing does (it calls the same snprintf); only the
 * exponent is rewritten (letter E, sign, three digits). The test suite `hostile` compares the
 * two texts over zero, subnormals, the extremes and random bit patterns. */
#include <stdio.h>
#include <string.h>

/* x (finite) into out[0..24]: right-justified in 25 characters, the first one a blank. */
void exic_c_es24_16e3(double x, char *out)
{
    char b[40];
    int n = snprintf(b, sizeof b, "%.16e", x);      /* [-]d.dddddddddddddddde[+-]dd[d] */
    int mant = 18 + (b[0] == '-');                  /* characters before the 'e' */
    int edigits = n - mant - 2;                     /* 2 or 3 */
    char *o = out + 25 - (mant + 5);
    memset(out, ' ', 25);
    memcpy(o, b, mant);
    o += mant;
    *o++ = 'E';
    *o++ = b[mant + 1];
    if (edigits == 2) {
        *o++ = '0';
        memcpy(o, b + mant + 2, 2);
    } else {
        memcpy(o, b + mant + 2, 3);
    }
}
