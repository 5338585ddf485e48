/* Field types: parse the text of a non-empty field, false when it does not fit the type. */

/* Appends the digits at *p to *value; returns how many there were (at most `room`: a longer
   run makes the caller fail). */
static size_t take_digits(const char **p, const char *end, int64_t *value, size_t room)
{
    const char *s = *p;
    int64_t v = *value;
    while (s < end && is_digit(*s) && (size_t)(s - *p) < room)
        v = v * 10 + (*s++ - '0');
    *value = v;
    room = (size_t)(s - *p);
    *p = s;
    return room;
}

/* [+-]digits[.digits] (no point for an integer), at most NMEA_NUMBER_DIGITS digits. */
NMEA_FRAME bool parse_number(nmea_text t, bool integer, nmea_number *out)
{
    const char *p = t.ptr, *end = t.ptr + t.len;
    size_t whole, frac = 0;
    int64_t digits = 0;
    char sign = 0;
    bool point = false;

    if (p < end && (*p == '+' || *p == '-'))
        sign = *p++;
    whole = take_digits(&p, end, &digits, NMEA_NUMBER_DIGITS);
    if (p < end && *p == '.' && !integer) {
        point = true;
        p++;
        frac = take_digits(&p, end, &digits, NMEA_NUMBER_DIGITS - whole);
    }
    if (p != end || whole + frac == 0)
        return false;
    out->digits = (nmea_digits)digits;
    out->scale = (uint8_t)frac;
    out->width = (uint8_t)whole;
    out->sign = sign;
    out->point = point;
    out->present = true;
    return true;
}

/* Compares a * 10^-as with b * 10^-bs (both signed): -1, 0 or 1. No division (a Cortex-M links
   one of 64 bits as a library routine of 700 bytes): the magnitudes are brought to one scale, and
   one that would pass 2^64 on the way is the larger. */
static int compare_fixed(int64_t a, unsigned as, int64_t b, unsigned bs)
{
    uint64_t ma, mb;
    int order;
    if ((a < 0) != (b < 0))
        return a < 0 ? -1 : 1;
    if (as == bs) /* the common case: an integer against integer bounds */
        return a < b ? -1 : a > b;
    ma = a < 0 ? 0 - (uint64_t)a : (uint64_t)a;
    mb = b < 0 ? 0 - (uint64_t)b : (uint64_t)b;
    for (; as < bs; as++, ma *= 10)
        if (ma > UINT64_MAX / 10)
            return a < 0 ? -1 : 1;
    for (; bs < as; bs++, mb *= 10)
        if (mb > UINT64_MAX / 10)
            return a < 0 ? 1 : -1;
    order = ma < mb ? -1 : ma > mb;
    return a < 0 ? -order : order;
}

/* Whether `n` is within `range` (NULL: any value). */
NMEA_INLINE bool in_range(const nmea_number *n, const nmea_range *range)
{
    int64_t value;
    if (!range)
        return true;
    value = n->sign == '-' ? -n->digits : n->digits;
    if (range->has_min && (n->scale == range->min_scale ? value < range->min
                           : compare_fixed(value, n->scale, range->min, range->min_scale) < 0))
        return false;
    if (range->has_max && (n->scale == range->max_scale ? value > range->max
                           : compare_fixed(value, n->scale, range->max, range->max_scale) > 0))
        return false;
    return true;
}

int64_t nmea_number_scaled(const nmea_number *n, unsigned scale)
{
    int64_t v = n->digits;
    unsigned s = n->scale;
    while (s > scale) {
        v /= 10;
        s--;
    }
    while (s < scale) {
        v *= 10;
        s++;
    }
    return n->sign == '-' ? -v : v;
}

nmea_number nmea_number_of(int64_t value, unsigned scale)
{
    nmea_number n;
    uint64_t magnitude = value < 0 ? (uint64_t)0 - (uint64_t)value : (uint64_t)value, whole;
    if (scale > NMEA_MAX_DIGITS)
        scale = NMEA_MAX_DIGITS;
    whole = magnitude / (uint64_t)POW10(scale);
    n.digits = (nmea_digits)magnitude;
    n.scale = (uint8_t)scale;
    for (n.width = 1; whole >= 10; whole /= 10)
        n.width++;
    n.sign = value < 0 ? '-' : 0;
    n.point = scale > 0;
    n.present = true;
    return n;
}

NMEA_FRAME bool parse_hex(nmea_text t, nmea_hex *out)
{
    size_t i;
    uint64_t value = 0;
    bool lower = false, upper = false;
    if (t.len > 16)
        return false;
    for (i = 0; i < t.len; i++) {
        int d = hex_value(t.ptr[i]);
        if (d < 0)
            return false;
        lower = lower || (t.ptr[i] >= 'a' && t.ptr[i] <= 'f');
        upper = upper || (t.ptr[i] >= 'A' && t.ptr[i] <= 'F');
        value = value * 16 + (uint64_t)d;
    }
    if (lower && upper)
        return false;
    out->value = value;
    out->digits = (uint8_t)t.len;
    out->lower = lower;
    out->present = true;
    return true;
}

static unsigned two_digits(const char *p)
{
    return (unsigned)((p[0] - '0') * 10 + (p[1] - '0'));
}

static bool all_digits(const char *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (!is_digit(p[i]))
            return false;
    return true;
}

/* A time whose first six bytes at `t` are digits, with `frac` fraction digits worth `fraction`:
   checked and stored in `out`. */
NMEA_HOT bool time_of(const char *t, uint32_t fraction, size_t frac, bool point, nmea_time *out)
{
    out->hour = (uint8_t)two_digits(t);
    out->minute = (uint8_t)two_digits(t + 2);
    out->second = (uint8_t)two_digits(t + 4);
    if (out->hour > 23 || out->minute > 59 || out->second > 60)
        return false;
    out->fraction = fraction;
    out->fraction_digits = (uint8_t)frac;
    out->point = point;
    out->present = true;
    return true;
}

/* hhmmss[.f...], at most 9 fraction digits. */
NMEA_FRAME bool parse_time(nmea_text t, nmea_time *out)
{
    size_t frac = 0, i;
    uint32_t fraction = 0;
    bool point = t.len > 6 && t.ptr[6] == '.';
    if (t.len < 6 || !all_digits(t.ptr, 6) || (t.len > 6 && !point))
        return false;
    if (point) {
        frac = t.len - 7;
        if (frac > 9 || !all_digits(t.ptr + 7, frac))
            return false;
        for (i = 0; i < frac; i++)
            fraction = fraction * 10 + (uint32_t)(t.ptr[7 + i] - '0');
    }
    return time_of(t.ptr, fraction, frac, point, out);
}

/* A date ddmmyy whose six bytes at `t` are digits: checked and stored in `out`. */
NMEA_HOT bool date_of(const char *t, nmea_date *out)
{
    out->day = (uint8_t)two_digits(t);
    out->month = (uint8_t)two_digits(t + 2);
    out->year = (uint8_t)two_digits(t + 4);
    if (out->day < 1 || out->day > 31 || out->month < 1 || out->month > 12)
        return false;
    out->present = true;
    return true;
}

NMEA_FRAME bool parse_date(nmea_text t, nmea_date *out)
{
    return t.len == 6 && all_digits(t.ptr, 6) && date_of(t.ptr, out);
}

/* A coordinate's value read as `whole` digits before the point (worth `whole_value`) and `frac`
   after it (the minutes, fraction included, worth `minutes`): checked and stored in `out`. */
NMEA_HOT bool coordinate_of(uint32_t whole_value, size_t whole, uint64_t minutes, size_t frac, bool point,
                            unsigned max_degree_digits, unsigned max_degrees, nmea_coordinate *out)
{
    if (whole < 2 || whole > 2 + max_degree_digits || frac > NMEA_NUMBER_DIGITS - 2)
        return false;
    if (whole_value / 100 > max_degrees || minutes > (uint64_t)(60 * POW10(frac)))
        return false;
    out->degrees = (uint16_t)(whole_value / 100); /* whole <= 5 digits: no 64-bit division */
    out->degree_digits = (uint8_t)(whole - 2);
    out->minutes.digits = (nmea_digits)minutes;
    out->minutes.scale = (uint8_t)frac;
    out->minutes.width = 2;
    out->minutes.sign = 0;
    out->minutes.point = point;
    out->minutes.present = true;
    out->present = true;
    return true;
}

/* ddmm.mmmm (latitude) or dddmm.mmmm (longitude): the two digits before the point are whole
   minutes, the digits before them degrees. A leaf: at -Os inlined in read_coordinate, its only
   caller, so that its frame is not added below that reader's on nmea_parse's deepest path. */
NMEA_LEAF bool parse_coordinate(nmea_text t, unsigned max_degree_digits, unsigned max_degrees, nmea_coordinate *out)
{
    const char *p = t.ptr, *end = t.ptr + t.len, *point = NULL;
    uint32_t whole_value = 0; /* unsigned: digits too many for it are refused below (by their count) */
    uint64_t minutes;
    size_t whole, frac = 0;

    for (; p < end && is_digit(*p); p++)
        whole_value = whole_value * 10 + (uint32_t)(*p - '0');
    whole = (size_t)(p - t.ptr);
    minutes = whole_value % 100; /* of more digits than fit, coordinate_of refuses it */
    if (p < end && *p == '.') {
        for (point = p++; p < end && is_digit(*p); p++)
            minutes = minutes * 10 + (uint64_t)(*p - '0');
        frac = (size_t)(p - point - 1);
    }
    return p == end && coordinate_of(whole_value, whole, minutes, frac, point != NULL, max_degree_digits, max_degrees,
                                     out);
}

/* Whether a code the table does not know is still well formed for it: the same length range
   and character class as the known codes (never, for a closed table). */
static bool is_code_like(const nmea_enum_def *def, const char *p, size_t n, size_t min_len, size_t max_len)
{
    size_t i;
    if (def->code_class == NMEA_CODES_CLOSED || n < min_len || n > max_len)
        return false;
    for (i = 0; i < n; i++) {
        if (def->code_class == NMEA_CODES_DIGITS ? !is_digit(p[i])
            : def->code_class == NMEA_CODES_LETTERS ? !is_letter(p[i]) : !is_alnum(p[i]))
            return false;
    }
    return true;
}

static int enum_find(const nmea_enum_def *def, const char *p, size_t n)
{
    int i;
    size_t k;
    for (i = 0; i < def->count; i++) {
        const char *code = def->codes[i].code;
        for (k = 0; k < n && code[k] != 0 && code[k] == p[k]; k++) /* a NUL in `p` ends no code */
            continue;
        if (k == n && code[n] == 0)
            return i;
    }
    return NMEA_UNKNOWN_CODE;
}

/* The code whose text is `t` in upper case (the words of a text command). */
NMEA_INTERNAL int enum_find_upper(const nmea_enum_def *def, nmea_text t)
{
    int i;
    for (i = 0; i < def->count; i++)
        if (upper_is(t, def->codes[i].code))
            return i;
    return NMEA_UNKNOWN_CODE;
}

int nmea_enum_lookup(const nmea_enum_def *def, char code)
{
    return enum_find(def, &code, 1);
}

nmea_enum nmea_enum_of(const nmea_enum_def *def, int value)
{
    nmea_enum e;
    memset(&e, 0, sizeof e);
    e.value = value;
    e.present = true;
    if (value >= 0 && value < def->count && strlen(def->codes[value].code) <= NMEA_CODE_MAX)
        strcpy(e.code, def->codes[value].code);
    return e;
}

const char *nmea_enum_id(const nmea_enum_def *def, const nmea_enum *e)
{
    if (!e->present || e->value < 0 || e->value >= def->count)
        return NULL;
    return def->codes[e->value].id;
}
