/* The fast path: a sentence in its usual form, read in one pass without the bookkeeping errors
   need. nmea_parse_ex tries it first; whatever it is not sure of (any field it cannot read, a
   field count that fits no layout, an unusual frame) it leaves to the general path (layout.c's
   read_with), which then reads the line from the start and finds the error. It accepts a subset
   of what the general path accepts and fills the struct exactly as the general path would: a
   build with NMEA_TEST_HOOKS checks that on every line it is given (nmea_parse_general). */

/* What a layout's fast reader found: the line read, or it cannot be this layout (its field
   count does not fit: the general path cannot read it with this layout either), or not sure. */
typedef enum { FAST_OK, FAST_NOT_THIS, FAST_UNSURE } fast_result;

static const unsigned char HEX_UPPER_VALUE[256] = { /* the value of an upper-case hex digit + 1; 0 */
    ['0'] = 1, ['1'] = 2, ['2'] = 3, ['3'] = 4, ['4'] = 5, ['5'] = 6, ['6'] = 7, ['7'] = 8, ['8'] = 9, ['9'] = 10,
    ['A'] = 11, ['B'] = 12, ['C'] = 13, ['D'] = 14, ['E'] = 15, ['F'] = 16};

/* The usual frame: '$', the body, and "*HH" with upper-case hex digits (or none) matching the
   body's XOR, NMEA_MAX_LINE bytes at most, the address followed by a comma. Sets the number of
   fields. The body is read 8 bytes at a time, its last bytes as the word that ends them; what
   it holds is left to the fast readers: each stops at the ',' or '*' after its field, refuses
   what its type does not take (a reader that takes any byte refuses one that is not printable
   ASCII), and the layout's reader checks that its last field ends at the final '*' (a '*' in
   the body would end a field early). */
NMEA_HOT bool fast_frame(const char *line, size_t len, size_t *count)
{
    const char *body;
    size_t n, i, commas = 0;
    uint64_t word, sum = 0;
    unsigned high, low;

    /* (an overlong framed line has no bytes: `line` is then NULL) */
    if (len < 12 || len > NMEA_MAX_LINE || line[0] != '$' || line[len - 3] != '*')
        return false;
    body = line + 1;
    n = len - 4; /* at least 8 */
    for (i = 0; i + 8 <= n; i += 8) {
        memcpy(&word, body + i, 8);
        sum ^= word;
        commas += count_bytes(zero_bytes(word ^ (',' * BYTES_ONES)));
    }
    if (i < n) { /* the last n - i bytes: the top of the word that ends the body, moved down */
        unsigned shift = (unsigned)(8 * (8 - (n - i)));
        memcpy(&word, body + n - 8, 8);
        word >>= shift;
        sum ^= word;
        commas += count_bytes(zero_bytes(word ^ (',' * BYTES_ONES)) & (~UINT64_C(0) >> shift));
    }
    sum ^= sum >> 32;
    sum ^= sum >> 16;
    sum ^= sum >> 8;
    high = HEX_UPPER_VALUE[(unsigned char)line[len - 2]];
    low = HEX_UPPER_VALUE[(unsigned char)line[len - 1]];
    *count = commas;
    return high && low && (high - 1) * 16 + (low - 1) == (sum & 0xFF);
}

/* The field at *p, up to the ',' or '*' after it; *p then points past that separator. */
NMEA_HOT nmea_text fast_span(const char **p)
{
    const char *q = *p;
    nmea_text t;
    while (*q != ',' && *q != '*')
        q++;
    t = text_span(*p, q);
    *p = q + 1;
    return t;
}

/* fast_span for a field that takes any text: false when a byte of it is not printable. */
NMEA_HOT bool fast_printable_span(const char **p, nmea_text *out)
{
    const char *q = *p;
    while (*q != ',' && *q != '*') {
        if (!is_printable(*q))
            return false;
        q++;
    }
    *out = text_span(*p, q);
    *p = q + 1;
    return true;
}

/* An integer or decimal field in one pass: empty, or an optional '-', digits and (`integer`
   false) at most one point, NMEA_NUMBER_DIGITS digits in all, in `range`. This general form takes
   the fields fast_number leaves to it: a sign, or a point first. Returns where the next field
   starts, or NULL. (Not a pointer to the caller's position: that would keep it out of a
   register in every field's reader.) */
NMEA_RARE const char *fast_signed_number(const char *q, nmea_number *out, const nmea_range *range, bool integer)
{
    const char *digits_start, *point = NULL;
    uint64_t digits = 0; /* unsigned: a run too long for it is refused below, not undefined */
    unsigned digit;      /* unsigned: a byte below '0' wraps to a large value */
    size_t whole, count;
    nmea_number n;

    n.sign = *q == '-' ? '-' : 0;
    q += n.sign != 0;
    for (digits_start = q; (digit = (unsigned)(unsigned char)*q - '0') < 10; q++)
        digits = digits * 10 + digit;
    whole = (size_t)(q - digits_start);
    if (!integer && *q == '.')
        for (point = q++; (digit = (unsigned)(unsigned char)*q - '0') < 10; q++)
            digits = digits * 10 + digit;
    count = (size_t)(q - digits_start) - (point != NULL);
    if ((*q != ',' && *q != '*') || count > NMEA_NUMBER_DIGITS || (count == 0 && (point || n.sign)))
        return NULL;
    if (count) {
        n.digits = (nmea_digits)digits;
        n.scale = (uint8_t)(count - whole);
        n.width = (uint8_t)whole;
        n.point = point != NULL;
        n.present = true;
        if (!in_range(&n, range))
            return NULL;
        *out = n;
    }
    return q + 1;
}

/* fast_signed_number for the fields nearly every sentence holds: empty, or starting with a
   digit. Such a number has no sign and at least one digit, which spares the checks of both. (It
   fills the number as quick_number does; a helper shared by the two cost 5 instructions a line
   on the bench corpus, half a percent.) */
NMEA_HOT bool fast_number(const char **p, nmea_number *out, const nmea_range *range, bool integer)
{
    const char *start = *p, *q = start, *point = NULL;
    uint64_t digits;
    unsigned digit = (unsigned)(unsigned char)*q - '0'; /* unsigned: a byte below '0' wraps */
    size_t whole, count;
    nmea_number n;

    if (digit >= 10) {
        q = *q != ',' && *q != '*' ? fast_signed_number(q, out, range, integer) : q + 1;
        if (!q)
            return false;
        *p = q;
        return true;
    }
    for (digits = digit, q++; (digit = (unsigned)(unsigned char)*q - '0') < 10; q++)
        digits = digits * 10 + digit;
    whole = (size_t)(q - start);
    count = whole;
    if (!integer && *q == '.') {
        for (point = q++; (digit = (unsigned)(unsigned char)*q - '0') < 10; q++)
            digits = digits * 10 + digit;
        count = (size_t)(q - start) - 1;
    }
    if ((*q != ',' && *q != '*') || count > NMEA_NUMBER_DIGITS)
        return false;
    n.digits = (nmea_digits)digits;
    n.scale = (uint8_t)(count - whole);
    n.width = (uint8_t)whole;
    n.sign = 0;
    n.point = point != NULL;
    n.present = true;
    if (!in_range(&n, range))
        return false;
    *out = n;
    *p = q + 1;
    return true;
}

NMEA_HOT bool fast_integer(const char **p, nmea_number *out, const nmea_range *range)
{
    return fast_number(p, out, range, true);
}

NMEA_HOT bool fast_decimal(const char **p, nmea_number *out, const nmea_range *range)
{
    return fast_number(p, out, range, false);
}

NMEA_HOT bool fast_hex(const char **p, nmea_hex *out)
{
    nmea_text t = fast_span(p);
    return !t.len || parse_hex(t, out);
}

/* A time field in one pass, as parse_time reads it. (all_digits stops at the first byte that is
   not a digit, so nothing past the field's separator is read.) */
NMEA_HOT bool fast_time(const char **p, nmea_time *out)
{
    const char *t = *p, *q;
    uint32_t fraction = 0;
    unsigned digit; /* unsigned: a byte below '0' wraps to a large value */
    size_t frac = 0;
    bool point;

    if (*t == ',' || *t == '*') {
        *p = t + 1;
        return true;
    }
    if (!all_digits(t, 6))
        return false;
    q = t + 6;
    point = *q == '.';
    if (point) {
        for (q++; (digit = (unsigned)(unsigned char)*q - '0') < 10; q++)
            fraction = fraction * 10 + digit; /* wraps past 9 digits, which are refused */
        frac = (size_t)(q - t) - 7;
        if (frac > 9)
            return false;
    }
    if (*q != ',' && *q != '*')
        return false;
    *p = q + 1;
    return time_of(t, fraction, frac, point, out);
}

/* A date field in one pass, as parse_date reads it (nothing past its separator is read). */
NMEA_HOT bool fast_date(const char **p, nmea_date *out)
{
    const char *t = *p;

    if (*t == ',' || *t == '*') {
        *p = t + 1;
        return true;
    }
    if (!all_digits(t, 6) || (t[6] != ',' && t[6] != '*'))
        return false;
    *p = t + 7;
    return date_of(t, out);
}

/* A value field and a hemisphere field in one pass, as read_coordinate reads them. (The
   hemisphere's field has a separator of its own, so the value never ends at the final '*'.) */
NMEA_HOT bool fast_coordinate(const char **p, nmea_coordinate *out, char positive, char negative,
                              unsigned max_degree_digits, unsigned max_degrees)
{
    const char *start = *p, *q = start, *point = NULL;
    uint32_t whole_value = 0; /* unsigned: digits too many for it are refused below (by their count) */
    uint64_t minutes;
    unsigned digit;                    /* unsigned: a byte below '0' wraps to a large value */
    size_t whole, frac = 0;

    for (; (digit = (unsigned)(unsigned char)*q - '0') < 10; q++)
        whole_value = whole_value * 10 + digit;
    whole = (size_t)(q - start);
    minutes = whole_value % 100; /* of more digits than fit, coordinate_of refuses it */
    if (*q == '.') {
        for (point = q++; (digit = (unsigned)(unsigned char)*q - '0') < 10; q++)
            minutes = minutes * 10 + digit;
        frac = (size_t)(q - point - 1);
    }
    if (*q != ',' && *q != '*')
        return false;
    if (q == start) { /* no value: no hemisphere either */
        *p = q + 2;
        return q[1] == ',' || q[1] == '*';
    }
    if ((q[1] != positive && q[1] != negative) || (q[2] != ',' && q[2] != '*')
        || !coordinate_of(whole_value, whole, minutes, frac, point != NULL, max_degree_digits, max_degrees, out))
        return false;
    out->hemisphere = q[1];
    *p = q + 3;
    return true;
}

NMEA_HOT bool fast_latitude(const char **p, nmea_coordinate *out)
{
    return fast_coordinate(p, out, 'N', 'S', 2, 90);
}

NMEA_HOT bool fast_longitude(const char **p, nmea_coordinate *out)
{
    return fast_coordinate(p, out, 'E', 'W', 3, 180);
}

NMEA_HOT bool fast_char(const char **p, char *out)
{
    nmea_text t;
    if (!fast_printable_span(p, &t))
        return false;
    *out = t.len ? t.ptr[0] : 0;
    return t.len <= 1;
}

NMEA_HOT bool fast_literal(const char **p, bool *out, const char *literal)
{
    nmea_text t = fast_span(p);
    *out = t.len > 0;
    return !t.len || text_is(t, literal);
}

NMEA_HOT bool fast_keyword(const char **p, const char *keyword)
{
    return text_is(fast_span(p), keyword);
}

NMEA_HOT bool fast_text(const char **p, nmea_text *out, size_t max_length)
{
    return fast_printable_span(p, out) && (!max_length || out->len <= max_length);
}

/* A known code only: a code the table does not know is the general path's to keep. */
NMEA_HOT bool fast_enum(const char **p, nmea_enum *out, const nmea_enum_def *def)
{
    nmea_text t = fast_span(p);
    size_t i;
    if (!t.len)
        return true;
    if (t.len > def->max_len || (out->value = enum_find(def, t.ptr, t.len)) == NMEA_UNKNOWN_CODE)
        return false;
    for (i = 0; i < t.len; i++)
        out->code[i] = t.ptr[i];
    out->code[t.len] = 0;
    out->present = true;
    return true;
}

NMEA_HOT bool fast_enum_chars(const char **p, nmea_text *out, const nmea_enum_def *def, size_t max_length)
{
    size_t i;
    *out = fast_span(p);
    if (max_length && out->len > max_length)
        return false;
    for (i = 0; i < out->len; i++)
        if (enum_find(def, out->ptr + i, 1) == NMEA_UNKNOWN_CODE && !is_code_like(def, out->ptr + i, 1, 1, 1))
            return false;
    return true;
}

/* The optional trailing wire fields of a layout without a repeated group, when `count` fits. */
NMEA_HOT bool fast_count(size_t count, size_t fixed, size_t max, size_t *optional)
{
    *optional = count - fixed;
    return count >= fixed && count <= max;
}

/* read_group_count without its errors. */
NMEA_HOT bool fast_group_count(size_t count, size_t fixed, size_t width, size_t min, size_t max,
                               size_t optional_max, size_t *repeats, size_t *optional)
{
    size_t rest = count - fixed;
    if (count < fixed + min * width)
        return false;
    *repeats = rest / width < max ? rest / width : max;
    *optional = rest - *repeats * width;
    return *optional <= optional_max;
}
