/* Configuration parameter tables: the wire text of a value (Parameter.encode of the Python
   runtime). */

#ifndef NMEA_NO_TABLES
const nmea_parameter *nmea_param_find(const nmea_parameter *table, size_t count, unsigned number)
{
    size_t i;
    for (i = 0; i < count; i++)
        if (table[i].number == number)
            return &table[i];
    return NULL;
}

static bool param_refuse(const nmea_parameter *p, const char *pattern, nmea_error *err)
{
    fail(err, NMEA_ERR_BAD_VALUE, pattern);
    err->num[0] = p->number;
    err->str[0] = p->id;
    return false;
}

static bool param_encoding(const nmea_parameter *p, nmea_param_encoding encoding, nmea_error *err)
{
    static const char *const NAMES[] = {"hex", "decimal", "decimal_list", "text"};
    if (p->encoding == encoding)
        return true;
    param_refuse(p, ERROR_TEXT("parameter %n (%s) is written as %s"), err);
    err->str[1] = (unsigned)p->encoding < 4 ? NAMES[p->encoding] : "?";
    return false;
}

/* value * 10^-scale within the parameter's range. */
static bool param_in_range(const nmea_parameter *p, int64_t value, unsigned scale, nmea_error *err)
{
    if (p->range.has_min && compare_fixed(value, scale, p->range.min, p->range.min_scale) < 0)
        return param_refuse(p, ERROR_TEXT("parameter %n (%s): the value is below its minimum"), err);
    if (p->range.has_max && compare_fixed(value, scale, p->range.max, p->range.max_scale) > 0)
        return param_refuse(p, ERROR_TEXT("parameter %n (%s): the value is above its maximum"), err);
    return true;
}

static size_t param_finish(nmea_writer *w, nmea_error *err)
{
    size_t n = writer_finish(w);
    if (n == 0 && w->len) {
        fail(err, NMEA_ERR_TOO_LONG, ERROR_TEXT("the text needs %n bytes and a NUL, the buffer holds %n"));
        err->num[0] = w->len;
        err->num[1] = w->cap;
    }
    return n;
}

size_t nmea_param_hex(const nmea_parameter *p, uint64_t value, char *buf, size_t cap, nmea_error *err)
{
    nmea_writer w = writer_of(buf, cap);
    nmea_hex h;
    if (!param_encoding(p, NMEA_PARAM_HEX, err))
        return writer_finish(&w);
    if (value > (uint64_t)INT64_MAX) { /* above any bound an int64_t holds */
        if (p->range.has_max) {
            param_refuse(p, ERROR_TEXT("parameter %n (%s): the value is above its maximum"), err);
            return writer_finish(&w);
        }
    } else if (!param_in_range(p, (int64_t)value, 0, err)) {
        return writer_finish(&w);
    }
    if (p->size && p->size < 8 && value >> (8 * p->size)) {
        param_refuse(p, ERROR_TEXT("parameter %n (%s): the value does not fit %n byte(s)"), err);
        err->num[1] = p->size;
        return writer_finish(&w);
    }
    h.value = value;
    h.digits = 1;
    h.lower = false;
    h.present = true;
    hex_text(&w, &h);
    return param_finish(&w, err);
}

/* value * 10^-scale with `scale` decimals. */
static void param_number(nmea_writer *w, int64_t value, unsigned scale)
{
    uint64_t magnitude = value < 0 ? (uint64_t)0 - (uint64_t)value : (uint64_t)value;
    uint64_t unit = (uint64_t)POW10(scale);
    if (value < 0)
        put_char(w, '-');
    put_uint(w, magnitude / unit, 1);
    if (scale) {
        put_char(w, '.');
        put_uint(w, magnitude % unit, scale);
    }
}

static bool param_scale(const nmea_parameter *p, unsigned scale, nmea_error *err)
{
    if (scale <= NMEA_MAX_DIGITS)
        return true;
    return param_refuse(p, ERROR_TEXT("parameter %n (%s): more than 18 decimals"), err);
}

size_t nmea_param_decimal(const nmea_parameter *p, int64_t value, unsigned scale, char *buf, size_t cap,
                          nmea_error *err)
{
    nmea_writer w = writer_of(buf, cap);
    if (!param_encoding(p, NMEA_PARAM_DECIMAL, err) || !param_scale(p, scale, err)
        || !param_in_range(p, value, scale, err))
        return writer_finish(&w);
    param_number(&w, value, scale);
    return param_finish(&w, err);
}

size_t nmea_param_decimal_list(const nmea_parameter *p, const int64_t *values, size_t n, unsigned scale, char *buf,
                               size_t cap, nmea_error *err)
{
    nmea_writer w = writer_of(buf, cap);
    size_t i;
    if (!param_encoding(p, NMEA_PARAM_DECIMAL_LIST, err) || !param_scale(p, scale, err))
        return writer_finish(&w);
    if (p->count && n != p->count) {
        param_refuse(p, ERROR_TEXT("parameter %n (%s): expected %n values, got %n"), err);
        err->num[1] = p->count;
        err->num[2] = n;
        return writer_finish(&w);
    }
    for (i = 0; i < n; i++)
        if (!param_in_range(p, values[i], scale, err))
            return writer_finish(&w);
    for (i = 0; i < n; i++) {
        if (i)
            put_char(&w, ',');
        param_number(&w, values[i], scale);
    }
    return param_finish(&w, err);
}

size_t nmea_param_text(const nmea_parameter *p, const char *text, char *buf, size_t cap, nmea_error *err)
{
    nmea_writer w = writer_of(buf, cap);
    size_t i, n = strlen(text);
    if (!param_encoding(p, NMEA_PARAM_TEXT, err))
        return writer_finish(&w);
    if (p->max_length && n > p->max_length) {
        param_refuse(p, ERROR_TEXT("parameter %n (%s): text longer than %n"), err);
        err->num[1] = p->max_length;
        return writer_finish(&w);
    }
    for (i = 0; i < n; i++) {
        if (!is_printable(text[i]) || strchr(",*$!", text[i])) {
            param_refuse(p, ERROR_TEXT("parameter %n (%s): text holds ',', '*', '$', '!' or a byte outside printable ASCII"),
                         err);
            return writer_finish(&w);
        }
    }
    put_str(&w, text);
    return param_finish(&w, err);
}
#endif /* NMEA_NO_TABLES */
