/* TAG blocks (NMEA 0183 4.00, IEC 61162-450): `\code:value,...*hh\` before a sentence or on a
   line of their own. The blocks of a line are read (checked as the Python and Rust runtimes
   check them, with the same messages) and kept as their text, which the writer puts back as it
   is; the codes the spec names and their value types are the generated nmea_tag_codes. Left out
   by -DNMEA_NO_TAG_BLOCKS. */

#ifndef NMEA_NO_TAG_BLOCKS

/* What a value of each type that has a form must look like (a text takes anything). */
static const char *const TAG_FORMS[] = {[NMEA_TAG_INTEGER] = "digits", [NMEA_TAG_GROUP] = "n-m-id"};

static bool tag_fail(nmea_error *err, const char *pattern)
{
    return fail(err, NMEA_ERR_BAD_TAG_BLOCK, pattern);
}

/* 1 to NMEA_MAX_DIGITS digits from *p on, up to `end` or a '-'; *p moves past them. */
static bool tag_digits(const char **p, const char *end)
{
    const char *start = *p;
    while (*p < end && is_digit(**p))
        (*p)++;
    return *p > start && (size_t)(*p - start) <= NMEA_MAX_DIGITS;
}

/* An empty value fits any type; an integer is 1 to 18 digits, a group three of them joined by '-'. */
static bool tag_value_fits(nmea_tag_type type, nmea_text value)
{
    const char *p = value.ptr, *end = value.ptr + value.len;
    int parts = 1;
    if (!value.len || type == NMEA_TAG_TEXT)
        return true;
    if (type == NMEA_TAG_INTEGER)
        return tag_digits(&p, end) && p == end;
    for (;;) {
        if (!tag_digits(&p, end))
            return false;
        if (p == end)
            return parts == 3;
        p++; /* a '-' */
        parts++;
    }
}

const nmea_tag_code *nmea_tag_code_of(nmea_text code)
{
    const size_t count = NMEA_TAG_CODE_COUNT; /* a variable: a spec without codes compares with 0 */
    size_t i;
    for (i = 0; i < count; i++)
        if (text_is(code, nmea_tag_codes[i].code))
            return &nmea_tag_codes[i];
    return NULL;
}

bool nmea_tag_next_param(nmea_text *params, nmea_tag_param *out)
{
    const char *p = params->ptr, *end, *colon = NULL, *q;
    if (!p) /* past the last parameter */
        return false;
    end = p + params->len;
    for (q = p; q < end && *q != ','; q++)
        if (!colon && *q == ':')
            colon = q;
    out->code = text_span(p, colon ? colon : q);
    out->value = colon ? text_span(colon + 1, q) : text_span(q, q);
    *params = q < end ? text_span(q + 1, end) : nmea_text_of(NULL);
    return true;
}

bool nmea_tag_next_block(nmea_text *blocks, nmea_text *params)
{
    const char *p = blocks->ptr, *end = p + blocks->len, *star;
    if (!blocks->len || *p != '\\')
        return false;
    for (star = p + 1; star < end && *star != '*'; star++)
        continue;
    *params = text_span(p + 1, star);
    *blocks = text_span(star + 4 <= end ? star + 4 : end, end); /* past "*hh\" */
    return true;
}

bool nmea_tag_find(nmea_text blocks, const char *code, nmea_text *value)
{
    nmea_text params;
    nmea_tag_param param;
    while (nmea_tag_next_block(&blocks, &params))
        while (nmea_tag_next_param(&params, &param))
            if (text_is(param.code, code)) {
                *value = param.value;
                return true;
            }
    return false;
}

/* One block's parameters (between '\' and '*'): each a code of letters and digits, ':' and a
   value that fits the code's type. */
static bool check_tag_params(nmea_text body, nmea_error *err)
{
    nmea_tag_param param;
    const nmea_tag_code *known;
    size_t i;
    nmea_text rest = body; /* never NULL: an empty body is one empty parameter */
    while (nmea_tag_next_param(&rest, &param)) {
        bool named = param.code.len > 0 && param.value.ptr > param.code.ptr + param.code.len;
        for (i = 0; i < param.code.len; i++)
            named = named && is_alnum(param.code.ptr[i]);
        if (!named) {
            tag_fail(err, ERROR_TEXT("TAG block parameter %q is not code:value"));
            err->text = text_span(param.code.ptr, param.value.ptr + param.value.len);
            return false;
        }
        known = nmea_tag_code_of(param.code);
        if (known && !tag_value_fits(known->type, param.value)) {
            tag_fail(err, ERROR_TEXT("TAG block parameter %q: expected %s"));
            err->text = text_span(param.code.ptr, param.value.ptr + param.value.len);
            err->str[0] = TAG_FORMS[known->type];
            return false;
        }
    }
    return true;
}

/* The TAG blocks at the start of a line that starts with '\': their text in *blocks; after them
   the line holds a '$' or '!' sentence, or nothing. */
NMEA_INTERNAL bool read_tag_blocks(const char *line, size_t len, nmea_text *blocks, nmea_error *err)
{
    const char *p = line, *end = line + len, *close, *star;
    int high, low;
    bool lower, upper;
    unsigned sum;
    if (!all_printable(line, len, err))
        return false;
    while (p < end && *p == '\\') {
        for (close = p + 1; close < end && *close != '\\'; close++)
            continue;
        if (close == end)
            return tag_fail(err, ERROR_TEXT("TAG block has no closing backslash"));
        for (star = p + 1, sum = 0; star < close && *star != '*'; star++)
            sum ^= (unsigned char)*star;
        if (star == close) {
            tag_fail(err, ERROR_TEXT("TAG block %q has no checksum"));
            err->text = text_span(p + 1, close);
            return false;
        }
        high = close - star == 3 ? hex_value(star[1]) : -1;
        low = close - star == 3 ? hex_value(star[2]) : -1;
        lower = close - star == 3 && ((star[1] >= 'a' && star[1] <= 'f') || (star[2] >= 'a' && star[2] <= 'f'));
        upper = close - star == 3 && ((star[1] >= 'A' && star[1] <= 'F') || (star[2] >= 'A' && star[2] <= 'F'));
        if (high < 0 || low < 0 || (lower && upper)) {
            tag_fail(err, ERROR_TEXT("TAG block checksum %q is not two hex digits of one letter case"));
            err->text = text_span(star + 1, close);
            return false;
        }
        if ((unsigned)(high * 16 + low) != sum) {
            tag_fail(err, ERROR_TEXT("TAG block checksum is %t, computed %X"));
            err->text = text_span(star + 1, close);
            err->num[0] = sum;
            return false;
        }
        if (!check_tag_params(text_span(p + 1, star), err))
            return false;
        p = close + 1;
    }
    if (p < end && *p != '$' && *p != '!')
        return tag_fail(err, ERROR_TEXT("TAG block is followed by neither '$', '!' nor a TAG block"));
    *blocks = text_span(line, p);
    return true;
}

/* One block of `params`, its checksum in `style` (lower or upper case). */
static void put_tag_block(nmea_writer *w, const nmea_tag_param *params, size_t n, nmea_checksum_style style)
{
    size_t i;
    put_char(w, '\\');
    w->sum = 0;
    start_sum(w);
    for (i = 0; i < n; i++) {
        if (i)
            put_char(w, ',');
        put_text(w, params[i].code);
        put_char(w, ':');
        put_text(w, params[i].value);
    }
    stop_sum(w);
    put_char(w, '*');
    put_char(w, (style == NMEA_CHECKSUM_LOWER ? HEX_LOWER : HEX_UPPER)[w->sum >> 4]);
    put_char(w, (style == NMEA_CHECKSUM_LOWER ? HEX_LOWER : HEX_UPPER)[w->sum & 15]);
    put_char(w, '\\');
}

size_t nmea_tag_write(const nmea_tag_param *params, size_t n, nmea_checksum_style style, char *buf, size_t cap,
                      nmea_error *err)
{
    nmea_writer w = writer_of(buf, cap);
    nmea_text blocks;
    size_t len;
    put_tag_block(&w, params, n, style);
    len = writer_finish(&w);
    if (!len) {
        nmea_error_too_long(err, w.len);
        return 0;
    }
    if (!read_tag_blocks(buf, len, &blocks, err)) /* the text refused stays in buf */
        return 0;
    if (blocks.len != len) /* a '\\' in a parameter ended the block early */
        return tag_fail(err, ERROR_TEXT("TAG block parameter holds ',', '*' or a backslash"));
    return len;
}
#endif /* NMEA_NO_TAG_BLOCKS */
