/* The fast path of writing: a sentence without problems whose values are as a parser makes
   them, written with a local cursor and without the bookkeeping of nmea_writer (no per-byte
   capacity checks: each field first checks that the buffer has FAST_ROOM bytes left, which
   holds any field but a text, and a text checks its own length). Whatever else (a value only a
   hand-built struct has, a buffer nearly full) returns false and is left to the general writer,
   which then writes the whole sentence again; the output is the same byte for byte. */

/* The most bytes a fast_put_* other than a text writes, plus the checksum and the NUL. */
#define FAST_ROOM 64

typedef struct {
    char *buf;
    char *p;           /* the next byte */
    const char *limit; /* buf + cap - FAST_ROOM */
} fast_writer;

/* `n` bytes the caller has made room for: a word at a time, the last word overlapping the one
   before it, so that nothing is read or written outside the n bytes (a byte loop was a fifth
   of the writer's instructions). */
NMEA_HOT void fast_copy(fast_writer *w, const char *s, size_t n)
{
    char *p = w->p;
    uint64_t word;
    uint32_t half;
    size_t i;
    if (n >= 8) {
        for (i = 0; i + 8 < n; i += 8) {
            memcpy(&word, s + i, 8);
            memcpy(p + i, &word, 8);
        }
        memcpy(&word, s + n - 8, 8);
        memcpy(p + n - 8, &word, 8);
    } else if (n >= 4) {
        memcpy(&half, s, 4);
        memcpy(p, &half, 4);
        memcpy(&half, s + n - 4, 4);
        memcpy(p + n - 4, &half, 4);
    } else {
        for (i = 0; i < n; i++)
            p[i] = s[i];
    }
    w->p = p + n;
}

/* A text of `n` bytes, when it fits with FAST_ROOM bytes to spare (a separator may already
   have gone past the limit). */
NMEA_HOT bool fast_put_mem(fast_writer *w, const char *s, size_t n)
{
    if (n && (w->p > w->limit || n > (size_t)(w->limit - w->p)))
        return false;
    fast_copy(w, s, n);
    return true;
}

/* An enum's code (at most NMEA_CODE_MAX bytes). */
NMEA_HOT void fast_put_code(fast_writer *w, const char *s)
{
    char *p = w->p;
    while (*s)
        *p++ = *s++;
    w->p = p;
}

/* The separator of the next field, when there is room for it and any field but a text. */
NMEA_HOT bool fast_sep(fast_writer *w)
{
    if (w->p > w->limit)
        return false;
    *w->p++ = ',';
    return true;
}

NMEA_HOT bool fast_begin(fast_writer *w, char *buf, size_t cap, char start, nmea_text talker, const char *address)
{
    if (cap < FAST_ROOM + 1)
        return false;
    w->buf = buf;
    w->p = buf;
    w->limit = buf + cap - FAST_ROOM;
    *w->p++ = start;
    return fast_put_mem(w, talker.ptr, talker.len) && fast_put_mem(w, address, strlen(address));
}

/* The checksum (there is room for it and the NUL); returns the sentence's length. */
NMEA_HOT size_t fast_end(fast_writer *w, nmea_checksum_style style)
{
    unsigned char sum = xor_bytes(w->buf + 1, (size_t)(w->p - w->buf - 1));
    const char *hex = style == NMEA_CHECKSUM_LOWER ? HEX_LOWER : HEX_UPPER;
    if (style != NMEA_CHECKSUM_NONE) {
        *w->p++ = '*';
        if (style >= NMEA_CHECKSUM_SHORT_UPPER) { /* one digit, kept as received (rare) */
            w->p += checksum_digits(w->p, style, sum);
        } else if (style != NMEA_CHECKSUM_EMPTY) {
            w->p[0] = hex[sum >> 4];
            w->p[1] = hex[sum & 15];
            w->p += 2;
        }
    }
    *w->p = 0;
    return (size_t)(w->p - w->buf);
}

/* Puts the last `count` digits of `v` just before `end`, two at a time: what is left of `v`. */
NMEA_HOT uint64_t digits_before(char *end, uint64_t v, unsigned count)
{
    for (; count >= 2; count -= 2, v /= 100) {
        end -= 2;
        memcpy(end, DIGIT_PAIRS + v % 100 * 2, 2);
    }
    if (count) {
        end[-1] = (char)('0' + v % 10);
        v /= 10;
    }
    return v;
}

/* fast_number_text past its most common case, for the numbers a parser makes: not negative, no
   more digits than written (whole ones leading zeros included), NMEA_MAX_DIGITS at most, and
   decimals only after a point; written from the right in place. Out of line: the code of every
   number field would be much longer with it. */
NMEA_OUTLINE char *fast_any_number_text(char *p, const nmea_number *n)
{
    uint64_t v = (uint64_t)n->digits;
    unsigned count = (unsigned)n->width + n->scale;
    char *point, *end;
    if (n->digits < 0 || count > NMEA_MAX_DIGITS || v >= (uint64_t)POW10(count) || (n->scale && !n->point))
        return NULL;
    point = p + (n->sign != 0) + n->width;
    end = point + (n->point != 0) + n->scale;
    v = digits_before(end, v, n->scale);
    if (n->point)
        *point = '.';
    digits_before(point, v, n->width);
    if (n->sign)
        *p = n->sign;
    return end;
}

/* number_text for the numbers a parser makes; inline for the most common of all, an integer of
   at most 3 digits written with 1 to 3 (its conditions tested with |, one branch). */
NMEA_HOT bool fast_number_text(fast_writer *w, const nmea_number *n)
{
    uint64_t v = (uint64_t)n->digits;
    char *p = w->p;
    if (!n->present)
        return true;
    if ((n->scale | (unsigned char)n->sign | (unsigned)n->point) != 0 || v >= 1000 || (unsigned)n->width - 1 >= 3)
        return (w->p = fast_any_number_text(p, n)) != NULL;
    if (v >= 100 || n->width == 3) {
        *p++ = (char)('0' + v / 100);
        v %= 100;
    }
    if (v >= 10 || p != w->p || n->width == 2) {
        memcpy(p, DIGIT_PAIRS + v * 2, 2);
        p += 2;
    } else {
        *p++ = (char)('0' + v);
    }
    w->p = p;
    return true;
}

NMEA_HOT bool fast_put_number(fast_writer *w, const nmea_number *n)
{
    return fast_sep(w) && fast_number_text(w, n);
}

NMEA_HOT bool fast_put_hex(fast_writer *w, const nmea_hex *h)
{
    const char *hex = h->lower ? HEX_LOWER : HEX_UPPER;
    char *p;
    unsigned n = 1, i;
    uint64_t v = h->value;
    if (!fast_sep(w))
        return false;
    if (!h->present)
        return true;
    while (n < 16 && v >> (4 * n))
        n++;
    if (h->digits > 16)
        return false;
    if (n < h->digits)
        n = h->digits;
    p = w->p + n;
    for (i = 0; i < n; i++, v >>= 4)
        *--p = hex[v & 15];
    w->p += n;
    return true;
}

/* Two digits, for the parts of times and dates a parser makes (at most 99). */
NMEA_HOT bool fast_two_digits(fast_writer *w, unsigned v)
{
    if (v > 99)
        return false;
    memcpy(w->p, DIGIT_PAIRS + v * 2, 2);
    w->p += 2;
    return true;
}

NMEA_HOT bool fast_put_time(fast_writer *w, const nmea_time *t)
{
    char text[9], *end = text + sizeof text;
    if (!fast_sep(w))
        return false;
    if (!t->present)
        return true;
    if (!fast_two_digits(w, t->hour) || !fast_two_digits(w, t->minute) || !fast_two_digits(w, t->second)
        || t->fraction_digits > 9)
        return false;
    if (t->point) {
        *w->p++ = '.';
        if (t->fraction_digits) {
            if (t->fraction >= (uint64_t)POW10(t->fraction_digits))
                return false;
            fast_copy(w, uint_text(end, t->fraction, t->fraction_digits), t->fraction_digits);
        }
    }
    return true;
}

NMEA_HOT bool fast_put_date(fast_writer *w, const nmea_date *d)
{
    if (!fast_sep(w))
        return false;
    return !d->present
           || (fast_two_digits(w, d->day) && fast_two_digits(w, d->month) && fast_two_digits(w, d->year));
}

NMEA_HOT bool fast_put_coordinate(fast_writer *w, const nmea_coordinate *c)
{
    char text[3], *end = text + sizeof text;
    if (!fast_sep(w))
        return false;
    if (c->present) {
        if (c->degree_digits > 3 || c->degrees > 999 || (c->degree_digits && c->degrees >= POW10(c->degree_digits)))
            return false;
        if (c->degree_digits)
            fast_copy(w, uint_text(end, c->degrees, c->degree_digits), c->degree_digits);
        if (!fast_number_text(w, &c->minutes))
            return false;
    }
    *w->p++ = ',';
    if (c->present)
        *w->p++ = c->hemisphere;
    return true;
}

NMEA_HOT bool fast_put_char_field(fast_writer *w, char c)
{
    if (!fast_sep(w))
        return false;
    if (c)
        *w->p++ = c;
    return true;
}

/* A literal field: `literal` is `len` bytes. */
NMEA_HOT bool fast_put_literal(fast_writer *w, bool present, const char *literal, size_t len)
{
    return fast_sep(w) && (!present || fast_put_mem(w, literal, len));
}

NMEA_HOT bool fast_put_enum(fast_writer *w, const nmea_enum *e, const nmea_enum_def *def)
{
    if (!fast_sep(w))
        return false;
    if (e->present)
        fast_put_code(w, enum_code(e, def));
    return true;
}

/* A keyword field: `keyword` is `len` bytes. */
NMEA_HOT bool fast_put_keyword(fast_writer *w, const char *keyword, size_t len)
{
    return fast_sep(w) && fast_put_mem(w, keyword, len);
}

NMEA_HOT bool fast_put_text_field(fast_writer *w, nmea_text t)
{
    return fast_sep(w) && fast_put_mem(w, t.ptr, t.len);
}

/* The `fields` wire fields of a group's entries as received (nmea_entries.wire): false when the
   wire does not hold that many, or lenient parsing read some as empty, for the general writer. */
NMEA_HOT bool fast_put_entries(fast_writer *w, const nmea_entries *e, size_t fields)
{
    const char *p = e->wire.ptr;
    char *out;
    size_t i = 0, n = e->wire.len, seps = 0;
    uint64_t word;
    if (!fields)
        return true;
    if (!p || e->blanks || !fast_sep(w) || (n && (w->p > w->limit || n > (size_t)(w->limit - w->p))))
        return false;
    out = w->p;
    for (; i + 8 <= n; i += 8) { /* copied and their commas counted 8 bytes at a time */
        memcpy(&word, p + i, 8);
        memcpy(out + i, &word, 8);
        seps += count_bytes(zero_bytes(word ^ (',' * BYTES_ONES)));
    }
    for (; i < n; i++)
        seps += (out[i] = p[i]) == ',';
    w->p = out + n;
    return seps + 1 == fields; /* else the general writer writes the sentence again */
}
