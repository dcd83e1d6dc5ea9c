// The C++ side of exic_output_text_number (src/exic/output/text/number.f90): one real as the text of Fortran's
// `1x,es24.16e3` edit descriptor, for the rows of <stem>.his and <stem>.ene.
//
// std::to_chars(..., std::chars_format::scientific, 16) gives the 17 significant digits
// correctly rounded from the exact binary value, as printf's "%.16e" does (the C++ standard
// defines it so; libstdc++ implements it with Ryu printf, exact ties to even as glibc), and
// so the same digits as libgfortran's ES editing, which calls snprintf; only the exponent is
// rewritten (letter E, sign, three digits). It costs about a fifth of snprintf, which parses
// its format and goes through the stdio machinery for every value (doc/performance.md 6.5).
// The test suite `hostile` compares the text with Fortran's over zero, subnormals, the
// extremes, exact ties and random bit patterns.
#include <charconv>
#include <cstring>

// x (finite) into out[0..24]: right-justified in 25 characters, the first one a blank.
extern "C" void exic_c_es24_16e3(double x, char *out)
{
    char b[40];
    const std::to_chars_result r =
        std::to_chars(b, b + sizeof b, x, std::chars_format::scientific, 16);
    const int n = static_cast<int>(r.ptr - b);   // [-]d.dddddddddddddddde[+-]dd[d]
    const int mant = 18 + (b[0] == '-');         // characters before the 'e'
    const int edigits = n - mant - 2;            // 2 or 3
    char *o = out + 25 - (mant + 5);
    std::memset(out, ' ', 25);
    std::memcpy(o, b, mant);
    o += mant;
    *o++ = 'E';
    *o++ = b[mant + 1];
    if (edigits == 2) {
        *o++ = '0';
        std::memcpy(o, b + mant + 2, 2);
    } else {
        std::memcpy(o, b + mant + 2, 3);
    }
}
