// Decimal numbers of the text readers, fast and exactly as std::from_chars reads them: a number
// of at most 19 significant digits whose value fits 2^53 and whose decimal exponent is within
// +-22 is w * 10^e or w / 10^e, both exact doubles, in one correctly rounded operation (Clinger
// 1990, "How to read floating point numbers accurately"), so the result is the correctly rounded
// double that from_chars gives; anything else (more digits, a larger exponent, inf, nan, a form it
// does not know) goes to from_chars itself.
#pragma once

#include <charconv>
#include <cstdint>
#include <system_error>

namespace gpurt {

// The double of [first, last) as std::from_chars(first, last, value) reads it; true where all of
// the text is one number in range (from_chars consumed it all, no error).
inline bool parseDecimal(const char* first, const char* last, double& value) {
    static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                        1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const char* p = first;
    const bool negative = p < last && *p == '-';
    if (negative) ++p;
    uint64_t w = 0;
    int digits = 0, exponent = 0, mantissaDigits = 0;
    bool simple = true;
    for (; p < last && *p >= '0' && *p <= '9'; ++p, ++mantissaDigits) {
        if (w == 0 && *p == '0') continue;  // leading zeros count for nothing
        if (++digits > 19) simple = false;
        else w = w * 10 + uint64_t(*p - '0');
    }
    if (p < last && *p == '.') {
        for (++p; p < last && *p >= '0' && *p <= '9'; ++p, ++mantissaDigits) {
            --exponent;
            if (w == 0 && *p == '0') continue;
            if (++digits > 19) simple = false;
            else w = w * 10 + uint64_t(*p - '0');
        }
    }
    if (mantissaDigits == 0) simple = false;
    if (simple && p < last && (*p == 'e' || *p == 'E')) {
        const char* q = p + 1;
        const bool expNegative = q < last && *q == '-';
        if (q < last && (*q == '-' || *q == '+')) ++q;
        int e = 0, expDigits = 0;
        for (; q < last && *q >= '0' && *q <= '9'; ++q, ++expDigits)
            if (expDigits < 6) e = e * 10 + (*q - '0');
        if (expDigits == 0 || expDigits >= 6) simple = false;
        exponent += expNegative ? -e : e;
        p = q;
    }
    if (simple && p == last && w <= (uint64_t(1) << 53) && exponent >= -22 && exponent <= 22) {
        double v = double(w);
        if (w != 0) v = exponent < 0 ? v / kPow10[-exponent] : v * kPow10[exponent];
        value = negative ? -v : v;
        return true;
    }
    const auto [end, ec] = std::from_chars(first, last, value);
    return ec == std::errc() && end == last;
}

}  // namespace gpurt
