/* encode's JSON to wire text: JSON strings copied into the caller's scratch buffer, the members
   decode writes (required, nullable, a word, the checksum), and nmea_collector, which checks the
   texts of a sentence's "fields" and joins them with commas, the wire a layout then reads. Left
   out by -DNMEA_NO_JSON. */

#ifndef NMEA_NO_JSON
/* The bytes of JSON strings are copied into the caller's scratch buffer (a character beyond
   0xFF keeps its low byte, like the tools' escaping; `wide` tells). */
typedef struct {
    char *buf;
    size_t cap;
    size_t len;
} nmea_scratch;

static bool json_string(nmea_json v, nmea_scratch *s, nmea_text *out, bool *wide)
{
    const char *p = v.p + 1;
    long cp;
    size_t start = s->len;
    *wide = false;
    while (json_char_at(&p, v.end, &cp)) {
        if (s->len >= s->cap)
            return false;
        *wide = *wide || cp > 0xFF;
        s->buf[s->len++] = (char)(cp & 0xFF);
    }
    out->ptr = s->buf + start;
    out->len = s->len - start;
    return true;
}

/* The inside of a JSON string value, between its quotes. */
static nmea_text json_inside(nmea_json v)
{
    return text_span(v.p + 1, v.end - 1);
}

static bool bad_json(nmea_error *err, const char *pattern, const char *key)
{
    fail(err, NMEA_ERR_BAD_JSON, pattern);
    err->str[0] = key;
    return false;
}

static bool scratch_full(nmea_error *err)
{
    return bad_json(err, "the scratch buffer is too small for this line", NULL);
}

static bool json_require(nmea_json obj, const char *key, nmea_json *out, nmea_error *err)
{
    if (!json_member(obj, key, out))
        return bad_json(err, "missing \"%s\"", key);
    return true;
}

/* A member that must be a string (`nullable`: or null, then *present is false). */
static bool json_text_member(nmea_json obj, const char *key, bool nullable, nmea_scratch *s, nmea_text *out,
                             bool *present, bool *wide, nmea_error *err)
{
    nmea_json v;
    if (!json_require(obj, key, &v, err))
        return false;
    *present = false;
    *wide = false;
    if (nullable && json_is_null(v))
        return true;
    if (!json_is(v, '"'))
        return bad_json(err, nullable ? "\"%s\" is not a string or null" : "\"%s\" is not a string", key);
    if (!json_string(v, s, out, wide))
        return scratch_full(err);
    *present = true;
    return true;
}

/* How the "checksum" of decode's JSON says to write the checksum: null (none), "" (a bare '*'),
   lower case (when the text has a letter from a to z) or upper case, in one digit when the text
   is one character (a short checksum as received). */
static bool json_checksum_style(nmea_json root, nmea_checksum_style *style, nmea_error *err)
{
    nmea_json v;
    const char *p;
    long cp;
    size_t n = 0;
    bool lower = false;
    if (!json_require(root, "checksum", &v, err))
        return false;
    if (json_is_null(v)) {
        *style = NMEA_CHECKSUM_NONE;
        return true;
    }
    if (!json_is(v, '"'))
        return bad_json(err, "\"%s\" is not a string or null", "checksum");
    for (p = v.p + 1; json_char_at(&p, v.end, &cp); n++)
        lower = lower || (cp >= 'a' && cp <= 'z');
    if (n == 1)
        *style = lower ? NMEA_CHECKSUM_SHORT_LOWER : NMEA_CHECKSUM_SHORT_UPPER;
    else
        *style = n == 0 ? NMEA_CHECKSUM_EMPTY : lower ? NMEA_CHECKSUM_LOWER : NMEA_CHECKSUM_UPPER;
    return true;
}

/* A member that must be a string of ASCII letters and digits (an address, a talker ID, a command
   word), copied to the scratch buffer. */
static bool json_word_member(nmea_json obj, const char *key, nmea_scratch *s, nmea_text *out, nmea_error *err)
{
    nmea_json v;
    size_t i;
    bool wide;
    if (!json_require(obj, key, &v, err))
        return false;
    if (!json_is(v, '"'))
        return bad_json(err, "\"%s\" is not letters and digits", key);
    if (!json_string(v, s, out, &wide))
        return scratch_full(err);
    for (i = 0; i < out->len; i++)
        if (!is_alnum(out->ptr[i]))
            wide = true;
    if (wide || !out->len)
        return bad_json(err, "\"%s\" is not letters and digits", key);
    return true;
}

/* The talker of a standard sentence: two letters and digits, as decode gives it (a longer one
   would make another address). */
static bool json_talker_member(nmea_json obj, const char *sentence, nmea_scratch *s, nmea_text *out, nmea_error *err)
{
    if (!json_word_member(obj, "talker", s, out, err))
        return false;
    if (out->len != talker_length(sentence))
        return bad_json(err, talker_length(sentence) == 2 ? "\"talker\" is not two letters and digits"
                                                          : "\"talker\" is not four letters and digits", NULL);
    return true;
}

/* Collecting wire fields from the `fields` of decode's JSON: each text is checked and appended
   to the scratch buffer, comma separated, so that the layout's reader parses them like a line. */
typedef struct {
    nmea_scratch *scratch;
    size_t start;
    size_t count;
    nmea_error *err;
} nmea_collector;

/* The wire text of a field value of decode's JSON (a string or null; null is empty), checked and
   copied to the scratch buffer. */
static bool json_field_text(nmea_json v, nmea_scratch *s, nmea_text *out, nmea_error *err)
{
    bool wide;
    size_t i;
    *out = nmea_text_of(NULL);
    if (json_is_null(v))
        return true;
    if (!json_is(v, '"'))
        return bad_json(err, "a field value is not a string or null", NULL);
    if (!json_string(v, s, out, &wide))
        return scratch_full(err);
    for (i = 0; i < out->len; i++) {
        if (wide || !is_printable(out->ptr[i]) || out->ptr[i] == ',' || out->ptr[i] == '*') {
            bad_json(err, "field text %q holds ',', '*' or a byte outside printable ASCII", NULL);
            err->text = json_inside(v);
            err->text_json = true;
            return false;
        }
    }
    return true;
}

static bool collect_text(nmea_collector *c, nmea_json v)
{
    nmea_text t;
    if (c->count && c->scratch->len >= c->scratch->cap)
        return scratch_full(c->err);
    if (c->count)
        c->scratch->buf[c->scratch->len++] = ',';
    c->count++;
    return json_field_text(v, c->scratch, &t, c->err);
}

/* The texts of one field value: a string or null, or for latitude/longitude (width 2) null or
   an array of two. */
static bool collect_value(nmea_collector *c, nmea_json v, unsigned width)
{
    nmea_json first, second, rest;
    if (width == 1)
        return collect_text(c, v);
    if (json_is_null(v)) {
        nmea_json empty;
        empty.p = "null";
        empty.end = empty.p + 4;
        return collect_text(c, empty) && collect_text(c, empty);
    }
    rest = json_items(v);
    if (json_is(v, '[') && json_next(&rest, &first) && json_next(&rest, &second) && !json_next(&rest, &v))
        return collect_text(c, first) && collect_text(c, second);
    return bad_json(c->err, "a latitude or longitude is not null or an array of two", NULL);
}

/* A required field of an object (a layout's fields, a group entry). */
NMEA_INTERNAL bool collect_field(nmea_collector *c, nmea_json obj, const char *key, unsigned width)
{
    nmea_json v;
    return json_require(obj, key, &v, c->err) && collect_value(c, v, width);
}

/* An optional trailing field: its texts when the key is there, nothing otherwise. */
NMEA_INTERNAL bool collect_optional(nmea_collector *c, nmea_json obj, const char *key, unsigned width)
{
    nmea_json v;
    return !json_member(obj, key, &v) || collect_value(c, v, width);
}

/* The array of a repeated group, to walk with json_next. */
NMEA_INTERNAL bool collect_group(nmea_collector *c, nmea_json obj, const char *key, nmea_json *entries)
{
    if (!json_require(obj, key, entries, c->err))
        return false;
    if (!json_is(*entries, '['))
        return bad_json(c->err, "\"%s\" is not an array", key);
    *entries = json_items(*entries);
    return true;
}

static nmea_text collected(const nmea_collector *c)
{
    return text_span(c->scratch->buf + c->start, c->scratch->buf + c->scratch->len);
}
#endif /* NMEA_NO_JSON */
