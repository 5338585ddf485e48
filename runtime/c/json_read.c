/* Reading JSON (the `encode` direction): a validator for the whole text, then lookups that
   walk the validated text again. A value is the span [p, end) of its text. */

#ifndef NMEA_NO_JSON
typedef struct {
    const char *p;
    const char *end;
} nmea_json;

/* How deep arrays and objects may nest in what `encode` reads (and in its check whether a line is
   a failure to skip), as in every tool: deeper JSON is "not JSON". */
#define JSON_MAX_DEPTH 500

static const char *json_ws(const char *p, const char *end)
{
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r'))
        p++;
    return p;
}

static bool json_word(const char **p, const char *end, const char *word)
{
    size_t n = strlen(word);
    if ((size_t)(end - *p) < n || memcmp(*p, word, n) != 0)
        return false;
    *p += n;
    return true;
}

/* Reads one character of a JSON string at *p (after the opening quote): its code point in
   *cp; false at the closing quote or on an error (then *cp is -1). */
static bool json_char_at(const char **p, const char *end, long *cp)
{
    const char *s = *p;
    int i, d;
    long v = 0;
    *cp = -1;
    if (s >= end || *s == '"' || (unsigned char)*s < 0x20)
        return false;
    if (*s != '\\') {
        *cp = (unsigned char)*s;
        *p = s + 1;
        return true;
    }
    if (++s >= end)
        return false;
    switch (*s) {
    case '"': v = '"'; break;
    case '\\': v = '\\'; break;
    case '/': v = '/'; break;
    case 'b': v = '\b'; break;
    case 'f': v = '\f'; break;
    case 'n': v = '\n'; break;
    case 'r': v = '\r'; break;
    case 't': v = '\t'; break;
    case 'u':
        if (end - s < 5)
            return false;
        for (i = 1; i <= 4; i++) {
            if ((d = hex_value(s[i])) < 0)
                return false;
            v = v * 16 + d;
        }
        s += 4;
        /* a surrogate pair is one character */
        if (v >= 0xD800 && v <= 0xDBFF && end - s >= 7 && s[1] == '\\' && s[2] == 'u') {
            long low = 0;
            for (i = 3; i <= 6 && (d = hex_value(s[i])) >= 0; i++)
                low = low * 16 + d;
            if (i == 7 && low >= 0xDC00 && low <= 0xDFFF) {
                v = 0x10000 + ((v - 0xD800) << 10) + (low - 0xDC00);
                s += 6;
            }
        }
        break;
    default:
        return false;
    }
    *cp = v;
    *p = s + 1;
    return true;
}

/* Whether c stands for itself in a JSON string (no quote, backslash or control character). */
static bool json_plain(char c)
{
    return c != '"' && c != '\\' && (unsigned char)c >= 0x20;
}

/* Past the string starting at p (at its quote); NULL when it is not a valid string. Runs of plain
   characters are stepped over without decoding: every lookup walks the members' strings. */
static const char *json_string_end(const char *p, const char *end)
{
    long cp;
    p++;
    for (;;) {
        while (p < end && json_plain(*p))
            p++;
        if (p >= end || *p != '\\' || !json_char_at(&p, end, &cp))
            break;
    }
    return p < end && *p == '"' ? p + 1 : NULL;
}

static const char *json_number_end(const char *p, const char *end)
{
    if (p < end && *p == '-')
        p++;
    if (p < end && *p == '0')
        p++;
    else if (p < end && *p >= '1' && *p <= '9')
        while (p < end && is_digit(*p))
            p++;
    else
        return NULL;
    if (end - p >= 2 && *p == '.' && is_digit(p[1]))
        for (p++; p < end && is_digit(*p); p++)
            continue;
    if (p < end && (*p == 'e' || *p == 'E')) {
        const char *q = p + 1;
        if (q < end && (*q == '+' || *q == '-'))
            q++;
        if (q < end && is_digit(*q))
            for (p = q; p < end && is_digit(*p); p++)
                continue;
    }
    return p;
}

/* Whether `len` bytes are one JSON value (as Python's json.loads takes it, NaN and Infinity
   included); *root is the value without the surrounding white space. */
static bool json_parse(const char *text, size_t len, nmea_json *root)
{
    const char *p = text, *end = text + len;
    unsigned char stack[(JSON_MAX_DEPTH + 7) / 8] = {0};
    size_t depth = 0;
    bool object;

    p = json_ws(p, end);
    root->p = p;
    for (;;) {
        /* a value */
        if (p >= end)
            return false;
        if (*p == '{' || *p == '[') {
            if (depth >= JSON_MAX_DEPTH)
                return false;
            object = *p == '{';
            if (object)
                stack[depth / 8] |= (unsigned char)(1u << depth % 8);
            else
                stack[depth / 8] &= (unsigned char)~(1u << depth % 8);
            depth++;
            p = json_ws(p + 1, end);
            if (p < end && *p == (object ? '}' : ']')) {
                depth--;
                p++;
            } else if (object) {
                if (p >= end || *p != '"' || !(p = json_string_end(p, end)))
                    return false;
                p = json_ws(p, end);
                if (p >= end || *p != ':')
                    return false;
                p = json_ws(p + 1, end);
                continue;
            } else {
                continue;
            }
        } else if (*p == '"') {
            if (!(p = json_string_end(p, end)))
                return false;
        } else if (!(json_word(&p, end, "true") || json_word(&p, end, "false") || json_word(&p, end, "null")
                     || json_word(&p, end, "NaN") || json_word(&p, end, "Infinity")
                     || json_word(&p, end, "-Infinity"))) {
            if (!(p = json_number_end(p, end)))
                return false;
        }
        /* after a value: close containers, or go on to the next element */
        for (;;) {
            p = json_ws(p, end);
            if (depth == 0) {
                root->end = p;
                while (root->end > root->p && (root->end[-1] == ' ' || root->end[-1] == '\t'
                                               || root->end[-1] == '\n' || root->end[-1] == '\r'))
                    root->end--;
                return p == end;
            }
            object = (stack[(depth - 1) / 8] >> (depth - 1) % 8) & 1;
            if (p < end && *p == (object ? '}' : ']')) {
                depth--;
                p++;
                continue;
            }
            if (p >= end || *p != ',')
                return false;
            p = json_ws(p + 1, end);
            if (object) {
                if (p >= end || *p != '"' || !(p = json_string_end(p, end)))
                    return false;
                p = json_ws(p, end);
                if (p >= end || *p != ':')
                    return false;
                p = json_ws(p + 1, end);
            }
            break;
        }
    }
}

/* Past the (valid) value starting at p. */
static const char *json_skip(const char *p, const char *end)
{
    size_t depth = 0;
    do {
        if (*p == '"') {
            p = json_string_end(p, end);
        } else if (*p == '{' || *p == '[') {
            depth++;
            p++;
        } else if (*p == '}' || *p == ']') {
            depth--;
            p++;
        } else if (depth == 0) {
            while (p < end && *p != ',' && *p != ']' && *p != '}' && *p != ' ' && *p != '\t' && *p != '\n'
                   && *p != '\r')
                p++;
        } else {
            p++;
        }
    } while (depth > 0 && p < end);
    return p;
}

static bool json_is(nmea_json v, char first)
{
    return v.p < v.end && *v.p == first;
}

static bool json_is_null(nmea_json v)
{
    return v.end - v.p == 4 && memcmp(v.p, "null", 4) == 0;
}

/* Whether the JSON string at p (at its quote) is `key`. */
static bool json_key_is(const char *p, const char *end, const char *key)
{
    long cp;
    p++;
    for (;;) {
        if (p < end && json_plain(*p))
            cp = (unsigned char)*p++;
        else if (!json_char_at(&p, end, &cp))
            break;
        if (!*key || cp != (unsigned char)*key)
            return false;
        key++;
    }
    return *key == 0;
}

/* The member `key` of an object (the last one, as Python's dict keeps it); false when `obj` is
   not an object or has no such member. */
static bool json_member(nmea_json obj, const char *key, nmea_json *out)
{
    const char *p, *end = obj.end, *k;
    bool found = false;
    if (!json_is(obj, '{'))
        return false;
    p = json_ws(obj.p + 1, end);
    while (p < end && *p == '"') {
        k = p;
        p = json_ws(json_string_end(p, end), end) + 1;
        p = json_ws(p, end);
        if (json_key_is(k, end, key)) {
            out->p = p;
            out->end = json_skip(p, end);
            found = true;
        }
        p = json_ws(json_skip(p, end), end);
        if (p < end && *p == ',')
            p = json_ws(p + 1, end);
    }
    return found;
}

/* The elements of an array, to walk with json_next. */
static nmea_json json_items(nmea_json array)
{
    nmea_json items;
    items.p = json_ws(array.p + 1, array.end);
    items.end = array.end;
    return items;
}

/* The next element of the items of an array (false after the last). */
static bool json_next(nmea_json *iter, nmea_json *element)
{
    const char *p = iter->p;
    if (p >= iter->end || *p == ']')
        return false;
    element->p = p;
    element->end = json_skip(p, iter->end);
    p = json_ws(element->end, iter->end);
    if (p < iter->end && *p == ',')
        p = json_ws(p + 1, iter->end);
    iter->p = p;
    return true;
}

/* Whether a line of decode's output is a JSON object whose "ok" is false (encode skips it). */
bool nmea_json_is_failure(const char *json, size_t len)
{
    nmea_json root, ok;
    return json_parse(json, len, &root) && json_member(root, "ok", &ok) && ok.end - ok.p == 5
        && memcmp(ok.p, "false", 5) == 0;
}
#endif /* NMEA_NO_JSON */
