/* Writing fields back: each writes its comma and its text (nothing for an empty field). */

/* The text of a field lenient parsing left empty, in its place (the last problem naming it; a
   number kept outside its range is written from its value). */
NMEA_RARE bool put_problem(nmea_writer *w)
{
    const nmea_problem *found = NULL;
    size_t i;
    for (i = 0; i < w->problems->count && i < NMEA_MAX_PROBLEMS; i++)
        if (w->problems->list[i].field == w->field && w->problems->list[i].kind == NMEA_PROBLEM_LEFT_EMPTY)
            found = &w->problems->list[i];
    if (found)
        put_text(w, found->text);
    return found != NULL;
}

/* The separator before the next wire field; true when that field is a problem, whose text as
   received has then been written in place of the field's own. */
NMEA_INLINE bool put_sep(nmea_writer *w)
{
    if (w->len < w->quick_cap) { /* put_char, without the checks a full buffer or a text command needs */
        w->buf[w->len++] = w->sep;
        w->last = w->sep;
    } else {
        put_char(w, w->sep);
    }
    w->field++;
    return w->problems && w->problems->count && put_problem(w);
}

/* [sign][whole digits, `width` of them at least][.[`scale` decimals]], formatted backwards from
   the last decimal so that no division by a power of ten is needed. A scale beyond
   NMEA_MAX_DIGITS (only in a struct built by hand) is written as that many zeros. */
NMEA_RARE void any_number_text(nmea_writer *w, const nmea_number *n)
{
    char text[1 + NMEA_UINT_TEXT + 1 + 255], *end = text + sizeof text, *p = end;
    uint64_t v = (uint64_t)n->digits;
    unsigned i, decimals = n->scale <= NMEA_MAX_DIGITS ? n->scale : 0;
    if (!n->present)
        return;
    if (n->point) {
        for (i = decimals; i < n->scale; i++)
            *--p = '0';
        for (i = 0; i < decimals; i++) {
            *--p = (char)('0' + v % 10);
            v /= 10;
        }
        *--p = '.';
    } else if (n->scale && n->scale <= NMEA_MAX_DIGITS) {
        v /= (uint64_t)POW10(n->scale);
    }
    if (n->width)
        p = uint_text(p, v, n->width);
    if (n->sign)
        *--p = n->sign;
    put_mem(w, p, (size_t)(end - p));
}

/* The number of decimal digits of v (one for 0). */
NMEA_INLINE unsigned digit_count(uint64_t v)
{
    unsigned count = 1;
    while (count <= NMEA_MAX_DIGITS && v >= (uint64_t)POW10(count))
        count++;
    return count;
}

/* any_number_text for the decimals a parser makes: at most NMEA_MAX_DIGITS decimals and a
   whole part. */
static void decimal_text(nmea_writer *w, const nmea_number *n)
{
    char text[1 + 20 + 1 + NMEA_MAX_DIGITS], *end = text + sizeof text, *p = end;
    uint64_t v = (uint64_t)n->digits;
    unsigned i;
    if (n->digits < 0 || n->scale > NMEA_MAX_DIGITS || !n->width || n->width > 20 || !n->point) {
        any_number_text(w, n);
        return;
    }
    for (i = 0; i < n->scale; i++) {
        *--p = (char)('0' + v % 10);
        v /= 10;
    }
    *--p = '.';
    p = uint_text(p, v, n->width);
    if (n->sign)
        *--p = n->sign;
    put_mem(w, p, (size_t)(end - p));
}

/* any_number_text, the integers a parser makes (no sign, some width) written straight into the
   buffer when it has room: their length is worked out first, then they are formatted
   backwards in place. */
NMEA_OUTLINE void integer_text(nmea_writer *w, const nmea_number *n)
{
    unsigned size;
    if (n->point || n->scale || n->sign || n->digits < 0 || !n->width || n->width > 20) {
        decimal_text(w, n);
        return;
    }
    size = digit_count((uint64_t)n->digits);
    if (size < n->width)
        size = n->width;
    if (w->len + size > w->quick_cap) { /* a full buffer, or a text command */
        any_number_text(w, n);
        return;
    }
    uint_text(w->buf + w->len + size, (uint64_t)n->digits, n->width);
    w->len += size;
    w->last = w->buf[w->len - 1];
}

/* integer_text, inline for the most common numbers of all: up to three digits and a width of
   at most three (satellite numbers, elevations, azimuths, signal strengths). */
NMEA_INLINE void number_text(nmea_writer *w, const nmea_number *n)
{
    uint64_t v = (uint64_t)n->digits; /* (a negative one is a huge value here) */
    unsigned value, size;
    char *end;
    if (!n->present)
        return;
    if (n->point || n->scale || n->sign || v >= 1000 || !n->width || n->width > 3 || w->len + 3 > w->quick_cap) {
        integer_text(w, n);
        return;
    }
    value = (unsigned)v;
    size = value >= 100 ? 3 : value >= 10 ? 2 : 1;
    if (size < n->width)
        size = n->width;
    end = w->buf + w->len + size;
    end[-1] = (char)('0' + value % 10);
    if (size >= 2)
        end[-2] = (char)('0' + value / 10 % 10);
    if (size == 3)
        end[-3] = (char)('0' + value / 100);
    w->len += size;
    w->last = end[-1];
}

NMEA_INTERNAL void put_number(nmea_writer *w, const nmea_number *n)
{
    if (!put_sep(w))
        number_text(w, n);
}

static void hex_text(nmea_writer *w, const nmea_hex *h)
{
    char digits[16];
    unsigned n = 0, width = h->digits;
    uint64_t v = h->value;
    const char *hex = h->lower ? HEX_LOWER : HEX_UPPER;
    do {
        digits[n++] = hex[v & 15];
        v >>= 4;
    } while (v);
    while (width > n) {
        put_char(w, '0');
        width--;
    }
    while (n)
        put_char(w, digits[--n]);
}

NMEA_INTERNAL void put_hex(nmea_writer *w, const nmea_hex *h)
{
    if (!put_sep(w) && h->present)
        hex_text(w, h);
}

static void time_text(nmea_writer *w, const nmea_time *t)
{
    char text[3 * 3 + 1 + NMEA_UINT_TEXT], *end = text + sizeof text, *p = end;
    if (t->point) {
        if (t->fraction_digits)
            p = uint_text(p, t->fraction, t->fraction_digits);
        *--p = '.';
    }
    p = uint_text(p, t->second, 2);
    p = uint_text(p, t->minute, 2);
    p = uint_text(p, t->hour, 2);
    put_mem(w, p, (size_t)(end - p));
}

NMEA_INTERNAL void put_time(nmea_writer *w, const nmea_time *t)
{
    if (!put_sep(w) && t->present)
        time_text(w, t);
}

static void date_text(nmea_writer *w, const nmea_date *d)
{
    char text[3 * 3], *end = text + sizeof text, *p = end;
    p = uint_text(p, d->year, 2);
    p = uint_text(p, d->month, 2);
    p = uint_text(p, d->day, 2);
    put_mem(w, p, (size_t)(end - p));
}

NMEA_INTERNAL void put_date(nmea_writer *w, const nmea_date *d)
{
    if (!put_sep(w) && d->present)
        date_text(w, d);
}

static void coordinate_text(nmea_writer *w, const nmea_coordinate *c)
{
    if (c->degree_digits)
        put_uint(w, c->degrees, c->degree_digits);
    number_text(w, &c->minutes);
}

NMEA_INTERNAL void put_coordinate(nmea_writer *w, const nmea_coordinate *c)
{
    if (!put_sep(w) && c->present)
        coordinate_text(w, c);
    if (!put_sep(w) && c->present)
        put_char(w, c->hemisphere);
}

NMEA_INTERNAL void put_char_field(nmea_writer *w, char c)
{
    if (!put_sep(w) && c)
        put_char(w, c);
}

NMEA_INTERNAL void put_literal(nmea_writer *w, bool present, const char *literal)
{
    if (!put_sep(w) && present)
        put_str(w, literal);
}

static const char *enum_code(const nmea_enum *e, const nmea_enum_def *def)
{
    return e->value >= 0 && e->value < def->count ? def->codes[e->value].code : e->code;
}

NMEA_INTERNAL void put_enum(nmea_writer *w, const nmea_enum *e, const nmea_enum_def *def)
{
    if (!put_sep(w) && e->present)
        put_str(w, enum_code(e, def));
}

NMEA_INTERNAL void put_keyword(nmea_writer *w, const char *keyword)
{
    if (!put_sep(w))
        put_str(w, keyword);
}

NMEA_INTERNAL void put_text_field(nmea_writer *w, nmea_text t)
{
    if (!put_sep(w))
        put_text(w, t);
}
