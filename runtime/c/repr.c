/* Python's repr of a double, which its json module writes too: one piece pasted into each C pair
   that prints numbers as JSON (nmea.c's fixes, nmea_ais.c, nmea_ubx.c, nmea_rtcm3.c), so the
   three languages print every double alike. Needs <stdio.h> and <stdlib.h>. */

/* Python's repr of a finite `value` into `text` (NMEA_REPR_SIZE bytes), its length returned: the
   fewest significant digits that read back the same; of those, the closest to the value (a tie to
   even: printf's rounding), or, when that one does not read back (a power of two, whose lower
   neighbour is nearer), its neighbour in the last digit. Positional from 1e-4 to below 1e16, with
   ".0" when whole; else d.ddde-XX with two exponent digits or more. */
#define NMEA_REPR_SIZE 32
static size_t nmea_repr_double(double value, char *text)
{
    char scientific[40], digits[24];
    const char *p, *e;
    int count, n = 0, exponent, k;
    size_t len = 0;
    for (count = 1; count < 17; count++) {
        unsigned long long mantissa = 0, limit = 1;
        snprintf(scientific, sizeof scientific, "%.*e", count - 1, value);
        if (strtod(scientific, NULL) == value)
            break;
        e = strchr(scientific, 'e');
        for (p = scientific; p < e; p++)
            if (*p >= '0' && *p <= '9')
                mantissa = mantissa * 10 + (unsigned long long)(*p - '0');
        for (k = 1; k < count; k++)
            limit *= 10;
        for (k = -1; k <= 1; k += 2) {
            unsigned long long next = mantissa + (unsigned long long)k;
            char number[24], candidate[40];
            int width;
            if (next < limit || next >= 10 * limit)
                continue; /* a digit more or fewer: another exponent */
            width = snprintf(number, sizeof number, "%llu", next);
            snprintf(candidate, sizeof candidate, "%s%c%s%s%s", scientific[0] == '-' ? "-" : "", number[0],
                     width > 1 ? "." : "", number + 1, e);
            if (strtod(candidate, NULL) == value) {
                memcpy(scientific, candidate, sizeof candidate);
                count = 0; /* found */
                break;
            }
        }
        if (count == 0)
            break;
    }
    if (count == 17)
        snprintf(scientific, sizeof scientific, "%.16e", value);
    e = strchr(scientific, 'e');
    for (p = scientific; p < e; p++)
        if (*p >= '0' && *p <= '9')
            digits[n++] = *p;
    while (n > 1 && digits[n - 1] == '0')
        n--;
    exponent = atoi(e + 1);
    if (scientific[0] == '-')
        text[len++] = '-';
    if (exponent < -4 || exponent >= 16) {
        text[len++] = digits[0];
        if (n > 1) {
            text[len++] = '.';
            memcpy(text + len, digits + 1, (size_t)n - 1);
            len += (size_t)n - 1;
        }
        len += (size_t)snprintf(text + len, NMEA_REPR_SIZE - len, "e%c%02d", exponent < 0 ? '-' : '+',
                                exponent < 0 ? -exponent : exponent);
        return len;
    }
    if (exponent < 0) {
        text[len++] = '0';
        text[len++] = '.';
        for (k = 1; k < -exponent; k++)
            text[len++] = '0';
        memcpy(text + len, digits, (size_t)n);
        len += (size_t)n;
    } else {
        for (k = 0; k <= exponent; k++)
            text[len++] = k < n ? digits[k] : '0';
        text[len++] = '.';
        if (n > exponent + 1) {
            memcpy(text + len, digits + exponent + 1, (size_t)(n - exponent - 1));
            len += (size_t)(n - exponent - 1);
        } else
            text[len++] = '0';
    }
    text[len] = '\0';
    return len;
}
