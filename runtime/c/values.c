/* The field values as the numbers an application computes with: a number as a double or a float,
   a coordinate as degrees x 10^7, a time as milliseconds of the day, a date as days since
   1970-01-01 (two-digit years by NMEA_PIVOT_YEAR), a date and time as milliseconds since then.
   No heap, no libm, and no floating point but in nmea_to_double and nmea_to_float: the rest is
   exact integer arithmetic. Python and Rust give the same values (generated/vectors/values.jsonl). */

double nmea_to_double(const nmea_number *n)
{
    /* Both operands are exact doubles up to 2^53 digits (10^18 is one too), so one rounding:
       the nearest double for up to 15 significant digits. */
    int64_t digits = n->sign == '-' ? -n->digits : n->digits;
    return (double)digits / (double)POW10(n->scale);
}

float nmea_to_float(const nmea_number *n) { return (float)nmea_to_double(n); }

int32_t nmea_coordinate_e7(const nmea_coordinate *c)
{
    /* degrees x 10^7 + minutes x 10^7 / 60, where minutes = digits / 10^scale, rounded half
       away from zero. The minutes are at most 60 (digits <= 60 x 10^scale, scale <= 16), so
       neither branch overflows. */
    const nmea_number *m = &c->minutes;
    int64_t e7 = m->scale <= 7 ? (m->digits * POW10(7 - m->scale) + 30) / 60
                               : (m->digits + 30 * POW10(m->scale - 7)) / (60 * POW10(m->scale - 7));
    e7 += (int64_t)c->degrees * 10000000;
    return (int32_t)(c->hemisphere == 'S' || c->hemisphere == 'W' ? -e7 : e7);
}

uint32_t nmea_time_ms(const nmea_time *t)
{
    uint32_t seconds = ((uint32_t)t->hour * 60 + t->minute) * 60 + t->second;
    uint64_t ms = (uint64_t)t->fraction * 1000 / (uint64_t)POW10(t->fraction_digits);
    return seconds * 1000 + (uint32_t)ms;
}

int nmea_date_year(const nmea_date *d) { return d->year + (d->year < NMEA_PIVOT_YEAR ? 2000 : 1900); }

bool nmea_days_from_civil(int32_t year, int month, int day, int32_t *days)
{
    static const uint8_t MONTH_DAYS[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    if (year < 1 || year > 9999 || month < 1 || month > 12 || day < 1 ||
        day > MONTH_DAYS[month - 1] + (month == 2 && leap))
        return false;
    /* Days since 0000-03-01 (proleptic Gregorian), years counted from March so that a leap day
       ends its year (month lengths from March: 31 30 31 30 31 31 30 31 30 31 31 28/29, which
       (153 m + 2) / 5 sums), less the 719468 days to 1970-01-01. */
    int32_t y = year - (month <= 2);
    int32_t m = month <= 2 ? month + 9 : month - 3;
    int32_t day_of_year = (153 * m + 2) / 5 + day - 1;
    *days = y * 365 + y / 4 - y / 100 + y / 400 + day_of_year - 719468;
    return true;
}

bool nmea_date_days(const nmea_date *d, int32_t *days)
{
    return nmea_days_from_civil(nmea_date_year(d), d->month, d->day, days);
}

bool nmea_datetime_ms(const nmea_date *d, const nmea_time *t, int64_t *ms)
{
    int32_t days;
    if (!d->present || !t->present || t->second > 59 || !nmea_date_days(d, &days))
        return false;
    *ms = (int64_t)days * 86400000 + nmea_time_ms(t);
    return true;
}
