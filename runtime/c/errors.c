/* Errors: the kinds' names, `fail` and its helpers that fill an nmea_error, the message and name
   of an error written from its pattern (the texts of runtime/contract.yaml, byte for byte those
   of the Python and Rust runtimes), an error as JSON, and the problems of the sentences parsing keeps. */

static const char *const ERROR_KINDS[] = {
    "too_long", "not_a_sentence", "bad_tag_block", "bad_checksum", "checksum_mismatch", "missing_checksum",
    "too_few_fields", "too_many_fields", "bad_field", "bad_json", "bad_value",
};

const char *nmea_error_kind_name(nmea_error_kind kind)
{
    return (unsigned)kind < sizeof ERROR_KINDS / sizeof ERROR_KINDS[0] ? ERROR_KINDS[kind] : "unknown";
}

/* Resets `err` to an error of `kind` whose message is `pattern`; returns false. Directives:
   %q the text as a JSON string, %t the text as is, %s the next string, %n the next number,
   %X / %x the next number as two upper / lower case hex digits. */
static bool fail(nmea_error *err, nmea_error_kind kind, const char *pattern)
{
    memset(err, 0, sizeof *err);
    err->kind = kind;
    err->pattern = pattern;
    return false;
}

static void set_address(nmea_error *err, nmea_text address, const char *suffix)
{
    err->has_address = true;
    err->address = address;
    err->address_suffix = suffix;
}

void nmea_error_too_long(nmea_error *err, size_t len)
{
    fail(err, NMEA_ERR_TOO_LONG, ERROR_TEXT("line is %n bytes, the limit is %n"));
    err->num[0] = len;
    err->num[1] = NMEA_MAX_LINE;
}

#ifndef NMEA_NO_JSON
static bool json_char_at(const char **p, const char *end, long *cp);
#endif

/* The text of an error: bytes, or (text_json) the inside of a JSON string, whose characters
   above 0xFF are written as their low byte, escaped. */
static void put_error_text(nmea_writer *w, const nmea_error *err, int depth)
{
    const char *p = err->text.ptr, *end = p + err->text.len;
    long cp;
    if (!err->text_json) {
        put_escaped_mem(w, err->text.ptr, err->text.len, depth);
        return;
    }
#ifndef NMEA_NO_JSON /* only the JSON reader makes errors with text_json */
    while (json_char_at(&p, end, &cp))
        put_escaped_char(w, (char)(cp & 0xFF), cp > 0xFF, depth);
#else
    (void)p, (void)end, (void)cp;
#endif
}

static void put_message(nmea_writer *w, const nmea_error *err, int depth)
{
    const char *p = err->pattern ? err->pattern : nmea_error_kind_name(err->kind); /* terse: the kind */
    unsigned strs = 0, nums = 0;
    for (; *p; p++) {
        size_t n;
        if (*p != '%' || !p[1]) {
            put_escaped(w, *p, depth);
            continue;
        }
        switch (*++p) {
        case 'q':
            put_escaped(w, '"', depth);
            put_error_text(w, err, depth + 1);
            put_escaped(w, '"', depth);
            break;
        case 't':
            put_error_text(w, err, depth);
            break;
        case 's':
            if (strs < 2 && err->str[strs])
                put_escaped_mem(w, err->str[strs], strlen(err->str[strs]), depth);
            strs++;
            break;
        case 'n':
            put_uint(w, nums < 3 ? err->num[nums] : 0, 1);
            nums++;
            break;
        case 'X':
        case 'x':
            n = nums < 3 ? err->num[nums] : 0;
            put_char(w, (*p == 'X' ? HEX_UPPER : HEX_LOWER)[(n >> 4) & 15]);
            put_char(w, (*p == 'X' ? HEX_UPPER : HEX_LOWER)[n & 15]);
            nums++;
            break;
        default:
            put_escaped(w, *p, depth);
        }
    }
}

static void put_name(nmea_writer *w, const nmea_error *err)
{
    if (err->group) {
        put_str(w, err->group);
        put_char(w, '[');
        put_uint(w, err->entry, 1);
        put_str(w, "].");
    }
    put_str(w, err->name);
}

size_t nmea_error_message(const nmea_error *err, char *buf, size_t cap)
{
    nmea_writer w = writer_of(buf, cap);
    put_message(&w, err, 0);
    return writer_finish(&w);
}

size_t nmea_error_name(const nmea_error *err, char *buf, size_t cap)
{
    nmea_writer w = writer_of(buf, cap);
    if (!err->name) {
        writer_finish(&w);
        return 0;
    }
    put_name(&w, err);
    return writer_finish(&w);
}

#ifndef NMEA_NO_JSON
size_t nmea_error_to_json(const nmea_error *err, char *buf, size_t cap)
{
    nmea_writer w = writer_of(buf, cap);
    put_str(&w, "{\"ok\":false,\"error\":{\"kind\":\"");
    put_str(&w, nmea_error_kind_name(err->kind));
    put_str(&w, "\",\"address\":");
    if (err->has_address) {
        put_char(&w, '"');
        put_escaped_mem(&w, err->address.ptr, err->address.len, 1);
        if (err->address_suffix)
            put_escaped_mem(&w, err->address_suffix, strlen(err->address_suffix), 1);
        put_char(&w, '"');
    } else {
        put_str(&w, "null");
    }
    put_str(&w, ",\"field\":");
    if (err->field)
        put_uint(&w, err->field, 1);
    else
        put_str(&w, "null");
    put_str(&w, ",\"name\":");
    if (err->name) {
        put_char(&w, '"');
        put_name(&w, err);
        put_char(&w, '"');
    } else {
        put_str(&w, "null");
    }
    put_str(&w, ",\"message\":\"");
    put_message(&w, err, 1);
    put_str(&w, "\"}}");
    return writer_finish(&w);
}
#endif

/* A problem as the bad_field error it was. */
static void problem_error(const nmea_problem *p, nmea_error *err)
{
    fail(err, NMEA_ERR_BAD_FIELD, ERROR_TEXT("expected %s, found %q"));
    err->out_of_range = p->kind == NMEA_PROBLEM_OUT_OF_RANGE;
    err->field = p->field;
    err->group = p->group;
    err->entry = p->entry;
    err->name = p->name;
    err->str[0] = p->expected;
    err->text = p->text;
}

/* A bad_field error kept as a problem of `kind`. */
static void problem_of(nmea_problem *p, const nmea_error *err, nmea_problem_kind kind)
{
    p->field = (uint16_t)err->field;
    p->entry = (uint16_t)err->entry;
    p->kind = (uint8_t)kind;
    p->group = err->group;
    p->name = err->name;
    p->expected = err->str[0];
    p->text = err->text;
}

size_t nmea_problem_message(const nmea_problem *p, char *buf, size_t cap)
{
    nmea_error err;
    problem_error(p, &err);
    return nmea_error_message(&err, buf, cap);
}

size_t nmea_problem_name(const nmea_problem *p, char *buf, size_t cap)
{
    nmea_error err;
    problem_error(p, &err);
    return nmea_error_name(&err, buf, cap);
}
