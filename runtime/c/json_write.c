/* The fields as JSON: the lossless texts, or (values) the decoded values. Each writes
   [,]"key": (no key inside an array) and the value. Left out by -DNMEA_NO_JSON, with the JSON
   reader (json_read.c): the tools need them, a program that only parses and writes sentences
   does not. */

#ifndef NMEA_NO_JSON
static void put_json_cstr(nmea_writer *w, const char *s)
{
    put_json_str(w, nmea_text_of(s), 0);
}

static void json_key(nmea_writer *w, const char *key)
{
    if (w->last != '{' && w->last != '[')
        put_char(w, ',');
    if (key) {
        put_char(w, '"');
        put_str(w, key);
        put_str(w, "\":");
    }
}

NMEA_INTERNAL void json_open(nmea_writer *w, const char *key, char bracket)
{
    json_key(w, key);
    put_char(w, bracket);
}

NMEA_INTERNAL void json_close(nmea_writer *w, char bracket)
{
    put_char(w, bracket);
}

/* A JSON number for digits * 10^-scale, without leading or trailing zeros. */
static void decimal_json(nmea_writer *w, const nmea_number *n)
{
    uint64_t digits = (uint64_t)n->digits;
    uint64_t unit = (uint64_t)POW10(n->scale <= NMEA_MAX_DIGITS ? n->scale : 0);
    uint64_t frac = digits % unit;
    unsigned scale = n->scale;
    if (n->sign == '-' && digits)
        put_char(w, '-');
    put_uint(w, digits / unit, 1);
    if (frac) {
        while (frac % 10 == 0) {
            frac /= 10;
            scale--;
        }
        put_char(w, '.');
        put_uint(w, frac, scale);
    }
}

/* The text form of a value as a JSON string: the text is printable, so only '"' and '\' need
   escaping, and no value type writes them. */
#define JSON_TEXT(w, present, write) \
    do {                             \
        if (!(present)) {            \
            put_str(w, "null");      \
        } else {                     \
            put_char(w, '"');        \
            write;                   \
            put_char(w, '"');        \
        }                            \
    } while (0)

NMEA_INTERNAL void json_number(nmea_writer *w, const char *key, const nmea_number *n, bool values)
{
    json_key(w, key);
    if (values && n->present)
        decimal_json(w, n);
    else
        JSON_TEXT(w, n->present, number_text(w, n));
}

NMEA_INTERNAL void json_hex(nmea_writer *w, const char *key, const nmea_hex *h, bool values)
{
    json_key(w, key);
    if (values && h->present)
        put_uint(w, h->value, 1);
    else
        JSON_TEXT(w, h->present, hex_text(w, h));
}

NMEA_INTERNAL void json_time(nmea_writer *w, const char *key, const nmea_time *t, bool values)
{
    json_key(w, key);
    if (values && t->present) {
        put_char(w, '"');
        put_uint(w, t->hour, 2);
        put_char(w, ':');
        put_uint(w, t->minute, 2);
        put_char(w, ':');
        put_uint(w, t->second, 2);
        if (t->fraction_digits) {
            put_char(w, '.');
            put_uint(w, t->fraction, t->fraction_digits);
        }
        put_char(w, '"');
    } else {
        JSON_TEXT(w, t->present, time_text(w, t));
    }
}

NMEA_INTERNAL void json_date(nmea_writer *w, const char *key, const nmea_date *d, bool values)
{
    json_key(w, key);
    if (values && d->present) {
        put_char(w, '"');
        put_uint(w, d->year, 2);
        put_char(w, '-');
        put_uint(w, d->month, 2);
        put_char(w, '-');
        put_uint(w, d->day, 2);
        put_char(w, '"');
    } else {
        JSON_TEXT(w, d->present, date_text(w, d));
    }
}

NMEA_INTERNAL void json_coordinate(nmea_writer *w, const char *key, const nmea_coordinate *c, bool values)
{
    json_key(w, key);
    if (!c->present) {
        put_str(w, "null");
    } else if (values) {
        put_str(w, "{\"deg\":");
        put_uint(w, c->degrees, 1);
        put_str(w, ",\"min\":");
        decimal_json(w, &c->minutes);
        put_str(w, ",\"hemi\":");
        put_json_str(w, text_span(&c->hemisphere, &c->hemisphere + 1), 0);
        put_char(w, '}');
    } else {
        put_str(w, "[\"");
        coordinate_text(w, c);
        put_str(w, "\",");
        put_json_str(w, text_span(&c->hemisphere, &c->hemisphere + 1), 0);
        put_char(w, ']');
    }
}

NMEA_INTERNAL void json_char(nmea_writer *w, const char *key, char c, bool values)
{
    (void)values;
    json_key(w, key);
    if (c)
        put_json_str(w, text_span(&c, &c + 1), 0);
    else
        put_str(w, "null");
}

NMEA_INTERNAL void json_literal(nmea_writer *w, const char *key, bool present, const char *literal, bool values)
{
    (void)values;
    json_key(w, key);
    if (present)
        put_json_cstr(w, literal);
    else
        put_str(w, "null");
}

NMEA_INTERNAL void json_keyword(nmea_writer *w, const char *key, const char *keyword, bool values)
{
    (void)values;
    json_key(w, key);
    put_json_cstr(w, keyword);
}

NMEA_INTERNAL void json_text(nmea_writer *w, const char *key, nmea_text t, bool values)
{
    (void)values;
    json_key(w, key);
    if (t.len)
        put_json_str(w, t, 0);
    else
        put_str(w, "null");
}

NMEA_INTERNAL void json_enum(nmea_writer *w, const char *key, const nmea_enum *e, const nmea_enum_def *def, bool values)
{
    json_key(w, key);
    if (!e->present)
        put_str(w, "null");
    else if (values && e->value >= 0 && e->value < def->count)
        put_json_cstr(w, def->codes[e->value].id);
    else
        put_json_cstr(w, enum_code(e, def));
}

NMEA_INTERNAL void json_enum_chars(nmea_writer *w, const char *key, nmea_text t, const nmea_enum_def *def, bool values)
{
    size_t i;
    if (!values || !t.len) {
        json_text(w, key, t, values);
        return;
    }
    json_open(w, key, '[');
    for (i = 0; i < t.len; i++) {
        int value = enum_find(def, t.ptr + i, 1);
        json_key(w, NULL);
        if (value >= 0)
            put_json_cstr(w, def->codes[value].id);
        else
            put_json_str(w, text_span(t.ptr + i, t.ptr + i + 1), 0);
    }
    json_close(w, ']');
}

static void json_head(nmea_writer *w, nmea_text start, nmea_text address)
{
    put_str(w, "{\"ok\":true,\"start\":");
    put_json_str(w, start, 0);
    put_str(w, ",\"address\":");
    put_json_str(w, address, 0);
}

/* The rest of a known sentence's head, up to the opening brace of its fields. */
static void json_sentence_variant(nmea_writer *w, const char *sentence, const char *variant)
{
    put_str(w, ",\"sentence\":\"");
    put_str(w, sentence);
    put_str(w, "\",\"variant\":");
    if (variant)
        put_json_cstr(w, variant);
    else
        put_str(w, "null");
    put_str(w, ",\"fields\":{");
}

/* A known standard sentence up to the opening brace of its fields. */
NMEA_INTERNAL void json_begin_sentence(nmea_writer *w, char start, nmea_text talker, const char *sentence,
                                       const char *variant)
{
    put_str(w, start == '!' ? "{\"ok\":true,\"start\":\"!\",\"address\":\"" : "{\"ok\":true,\"start\":\"$\",\"address\":\"");
    put_escaped_mem(w, talker.ptr, talker.len, 1);
    put_str(w, sentence);
    put_str(w, "\",\"talker\":");
    put_json_str(w, talker, 0);
    json_sentence_variant(w, sentence, variant);
}

/* A proprietary sentence ("start" "$" or "" for a text command, no talker) up to the opening
   brace of its fields. */
NMEA_INTERNAL void json_begin_proprietary(nmea_writer *w, const char *start, nmea_text address, const char *sentence,
                                          const char *variant)
{
    json_head(w, nmea_text_of(start), address);
    put_str(w, ",\"talker\":null");
    json_sentence_variant(w, sentence, variant);
}

/* The address a text command shows: its word as received when it is written back as received
   (`sentence` wrote it), else the spec's. */
NMEA_INTERNAL nmea_text text_address(const nmea_writer *sentence, nmea_text as_received, const char *address)
{
    if (sentence->matched)
        return text_span(as_received.ptr, as_received.ptr + strlen(address));
    return nmea_text_of(address);
}

/* ,"checksum":"HH"} with the checksum `sum` the sentence is written with. */
static void json_checksum(nmea_writer *w, unsigned char sum, nmea_checksum_style style)
{
    char digits[2];
    put_str(w, ",\"checksum\":");
    if (style == NMEA_CHECKSUM_NONE) {
        put_str(w, "null}");
        return;
    }
    if (style == NMEA_CHECKSUM_EMPTY) {
        put_str(w, "\"\"}");
        return;
    }
    put_char(w, '"');
    put_mem(w, digits, checksum_digits(digits, style, sum));
    put_str(w, "\"}");
}

/* The short_checksum problem of a sentence whose checksum `sum` is written as one digit: what
   strict parsing refuses (bad_checksum) with the digit as its text. */
static void json_short_checksum(nmea_writer *w, unsigned char sum, nmea_checksum_style style)
{
    nmea_error err;
    char digit[2];
    fail(&err, NMEA_ERR_BAD_CHECKSUM, ERROR_TEXT("checksum %q is not two hex digits of one letter case"));
    err.text = text_span(digit, digit + checksum_digits(digit, style, sum));
    put_str(w, "{\"kind\":\"");
    put_str(w, "short_checksum");
    put_str(w, "\",\"field\":null,\"name\":null,\"text\":");
    put_json_str(w, err.text, 0);
    put_str(w, ",\"message\":\"");
    put_message(w, &err, 1);
    put_str(w, "\"}");
}

/* ,"problems":[...]: a checksum of one digit (when `style` and `sum` make one), then each number
   kept outside its range and each field lenient parsing left empty (`problems`, NULL: none), with
   its text and why. */
static void json_problems(nmea_writer *w, const nmea_problems *problems, unsigned char sum, nmea_checksum_style style)
{
    nmea_error err;
    size_t i;
    bool first = true;
    put_str(w, ",\"problems\":[");
    if (checksum_is_short(style, sum)) {
        json_short_checksum(w, sum, style);
        first = false;
    }
    for (i = 0; problems && i < problems->count && i < NMEA_MAX_PROBLEMS; i++, first = false) {
        problem_error(&problems->list[i], &err);
        put_str(w, first ? "{\"kind\":\"" : ",{\"kind\":\"");
        put_str(w, problems->list[i].kind == NMEA_PROBLEM_OUT_OF_RANGE ? "out_of_range" : "left_empty");
        put_str(w, "\",\"field\":");
        put_uint(w, err.field, 1);
        put_str(w, ",\"name\":");
        if (err.name) {
            put_char(w, '"');
            put_name(w, &err);
            put_char(w, '"');
        } else {
            put_str(w, "null");
        }
        put_str(w, ",\"text\":");
        put_json_str(w, err.text, 0);
        put_str(w, ",\"message\":\"");
        put_message(w, &err, 1);
        put_str(w, "\"}");
    }
    put_char(w, ']');
}

/* Closes the fields of a known sentence, lists its problems (NULL: none) and ends with its
   checksum; `sentence` is the writer that wrote it (for the checksum). */
NMEA_INTERNAL void json_end_sentence(nmea_writer *w, const nmea_writer *sentence, nmea_checksum_style style,
                                     const nmea_problems *problems)
{
    put_char(w, '}');
    if ((problems && problems->count) || checksum_is_short(style, sentence->sum))
        json_problems(w, problems, sentence->sum, style);
    json_checksum(w, sentence->sum, style);
}

/* A word of a text command's lossless fields that is a problem: its text in place of the
   field's (true), or nothing (false). */
NMEA_INTERNAL bool json_problem_word(nmea_writer *w, const char *key, const nmea_problems *problems, unsigned field)
{
    const nmea_problem *found = NULL;
    size_t i;
    for (i = 0; i < problems->count && i < NMEA_MAX_PROBLEMS; i++)
        if (problems->list[i].field == field)
            found = &problems->list[i];
    if (!found)
        return false;
    json_key(w, key);
    if (found->text.len)
        put_json_str(w, found->text, 0);
    else
        put_str(w, "null");
    return true;
}

static void json_generic(nmea_writer *w, const nmea_generic *g)
{
    nmea_writer sum = writer_of(NULL, 0);
    const char *p = g->fields.ptr, *end = p + g->fields.len, *comma;
    size_t i;
    write_generic(&sum, g);
    json_head(w, g->start, g->address);
    put_str(w, ",\"talker\":null,\"sentence\":null,\"variant\":null,\"fields\":[");
    for (i = 0; i < g->field_count; i++) {
        for (comma = p; comma < end && *comma != ','; comma++)
            continue;
        if (i)
            put_char(w, ',');
        put_json_str(w, text_span(p, comma), 0);
        p = comma < end ? comma + 1 : end;
    }
    put_char(w, ']');
    if (checksum_is_short(g->checksum, sum.sum))
        json_problems(w, NULL, sum.sum, g->checksum);
    json_checksum(w, sum.sum, g->checksum);
}
#endif /* NMEA_NO_JSON */
