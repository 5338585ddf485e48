/*
 * Runtime (hand-written: runtime/c/runtime.c): framing, checksum, field types, errors, JSON.
 *
 * The acceptance rules and messages here are shared byte for byte with the Python and Rust
 * runtimes (see docs/json.md). Everything below is static: the generated per-sentence code at
 * the end of this file is its only user, and the public functions are declared in nmea.h.
 */

#include <string.h>

#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__) /* -Os: the compiler's choices, for size */
#define NMEA_INTERNAL static __attribute__((unused))
#define NMEA_RARE static __attribute__((noinline, cold))
#define NMEA_HOT static inline
#define NMEA_OUTLINE static __attribute__((noinline))
#elif defined(__GNUC__)
#define NMEA_INTERNAL static __attribute__((unused))
#define NMEA_RARE static __attribute__((noinline, cold)) /* off the hot path */
#define NMEA_HOT static inline __attribute__((always_inline)) /* a few instructions per byte or field */
#define NMEA_OUTLINE static __attribute__((noinline))
#else
#define NMEA_INTERNAL static
#define NMEA_RARE static
#define NMEA_HOT static
#define NMEA_OUTLINE static
#endif

static const char HEX_UPPER[] = "0123456789ABCDEF";
static const char HEX_LOWER[] = "0123456789abcdef";

static const int64_t POW10[NMEA_MAX_DIGITS + 1] = {
    1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000, 1000000000,
    10000000000, 100000000000, 1000000000000, 10000000000000, 100000000000000,
    1000000000000000, 10000000000000000, 100000000000000000, 1000000000000000000,
};

static bool is_digit(char c) { return c >= '0' && c <= '9'; }
static bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
static bool is_alnum(char c) { return is_digit(c) || is_letter(c); }
static bool is_printable(char c) { return (unsigned char)c >= 0x20 && (unsigned char)c <= 0x7E; }

static int hex_value(char c)
{
    if (is_digit(c))
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

nmea_text nmea_text_of(const char *s)
{
    nmea_text t;
    t.ptr = s;
    t.len = s ? strlen(s) : 0;
    return t;
}

static nmea_text text_span(const char *begin, const char *end)
{
    nmea_text t;
    t.ptr = begin;
    t.len = (size_t)(end - begin);
    return t;
}

/* Byte by byte: the words compared are a few characters, shorter than a call to strlen. */
static bool text_is(nmea_text t, const char *s)
{
    size_t k;
    for (k = 0; k < t.len && s[k] && s[k] == t.ptr[k]; k++)
        continue;
    return k == t.len && s[k] == 0;
}

/* Whether a number field holds the integer `v` (no decimals), as a reply's pairing asks. */
static inline bool integer_is(nmea_number n, int64_t v)
{
    return n.present && n.scale == 0 && (n.sign == '-' ? -n.digits : n.digits) == v;
}

static char ascii_upper(char c)
{
    return c >= 'a' && c <= 'z' ? (char)(c - 'a' + 'A') : c;
}

/* Whether the upper-case form of `t` (ASCII letters only) is exactly `s`. */
static bool upper_is(nmea_text t, const char *s)
{
    size_t i, n = strlen(s);
    if (t.len != n)
        return false;
    for (i = 0; i < n; i++)
        if (ascii_upper(t.ptr[i]) != s[i])
            return false;
    return true;
}

/* ------------------------------------------------------------------------------------------ */
/* Writing text: a bounded buffer that keeps counting past its end and XORs the bytes written
   while `summing` (the checksum). The bytes kept in the buffer are summed once, when summing
   stops (from `sum_start` on); only those past its end (or with no buffer: decode's JSON writes
   a sentence just for its checksum) are summed as they come. Fields are preceded by `sep` (',',
   or ' ' between the words of a text command). While a text command is written, `match` is the
   command as received: the bytes
   written are compared with it ignoring case (`matched` stays true while they agree). While a
   sentence is written, `field` counts its wire fields, and the fields of its `problems` (those
   lenient parsing left empty) are written with their text as received. */

typedef struct {
    char *buf;
    size_t cap;
    size_t quick_cap; /* put_mem copies runs of bytes up to here: cap, or 0 to match a text command */
    size_t len;
    unsigned char sum;
    bool summing;
    size_t sum_start;
    char last;
    char sep;
    bool matched;
    const char *match;
    size_t match_len;
    size_t match_pos;
    size_t start;
    const nmea_problems *problems;
    unsigned field;
} nmea_writer;

static nmea_writer writer_of(char *buf, size_t cap)
{
    nmea_writer w;
    w.buf = buf;
    w.cap = buf ? cap : 0;
    w.quick_cap = w.cap;
    w.len = 0;
    w.sum = 0;
    w.summing = false;
    w.sum_start = 0;
    w.last = 0;
    w.sep = ',';
    w.matched = false;
    w.match = NULL;
    w.match_len = 0;
    w.match_pos = 0;
    w.start = 0;
    w.problems = NULL;
    w.field = 0;
    return w;
}

static void match_char(nmea_writer *w, char c)
{
    if (w->match_pos >= w->match_len || ascii_upper(w->match[w->match_pos]) != ascii_upper(c))
        w->matched = false;
    w->match_pos++;
}

static inline void put_char(nmea_writer *w, char c)
{
    if (w->len < w->cap)
        w->buf[w->len] = c;
    else if (w->summing)
        w->sum ^= (unsigned char)c;
    w->len++;
    if (w->match && w->summing)
        match_char(w, c);
    w->last = c;
}

static inline void put_mem(nmea_writer *w, const char *s, size_t n)
{
    size_t i;
    char *dst;
    if (n == 0)
        return;
    if (w->len + n > w->quick_cap) { /* a full buffer, or a text command */
        for (i = 0; i < n; i++)
            put_char(w, s[i]);
        return;
    }
    dst = w->buf + w->len; /* (a local pointer: a store through w->buf could change w) */
    for (i = 0; i < n; i++)
        dst[i] = s[i];
    w->len += n;
    w->last = s[n - 1];
}

/* The XOR of n bytes, a machine word at a time; when there are at least 8, the last n % 8 are
   the top of the word that ends them, moved down (no loop over single bytes to mispredict). */
static unsigned char xor_bytes(const char *p, size_t n)
{
    uint64_t word, acc = 0;
    unsigned char sum = 0;
    const char *end = p + n;
    if (n >= 8 && n % 8) {
        memcpy(&word, end - 8, 8);
        acc = word >> (8 * (8 - n % 8));
        n -= n % 8;
    }
    for (; n >= 8; p += 8, n -= 8) {
        memcpy(&word, p, 8);
        acc ^= word;
    }
    for (; n; n--)
        sum ^= (unsigned char)*p++;
    acc ^= acc >> 32;
    acc ^= acc >> 16;
    acc ^= acc >> 8;
    return (unsigned char)(sum ^ (unsigned char)acc);
}

static void start_sum(nmea_writer *w)
{
    w->summing = true;
    w->sum_start = w->len;
}

/* Sums the bytes kept since start_sum (the others are summed already). */
static void stop_sum(nmea_writer *w)
{
    size_t kept = w->len < w->cap ? w->len : w->cap;
    if (w->summing && w->sum_start < kept)
        w->sum ^= xor_bytes(w->buf + w->sum_start, kept - w->sum_start);
    w->summing = false;
}

static void put_str(nmea_writer *w, const char *s)
{
    size_t n = 0;
    while (s[n]) /* (short strings: codes, sentence ids, JSON keys) */
        n++;
    put_mem(w, s, n);
}

static void put_text(nmea_writer *w, nmea_text t)
{
    put_mem(w, t.ptr, t.len);
}

/* Writes `v` in decimal, zero-padded to at least `width` digits, just before `end`: returns
   where the text starts. Numbers are formatted backwards into a local buffer this way and then
   written in one put_mem. */
static const char DIGIT_PAIRS[] = "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
                                  "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
                                  "8081828384858687888990919293949596979899";

static inline char *uint_text(char *end, uint64_t v, unsigned width)
{
    char *p = end;
    uint32_t low;
    for (; v > UINT32_MAX; v /= 10)
        *--p = (char)('0' + v % 10);
    for (low = (uint32_t)v; low >= 100; low /= 100) { /* two digits per division */
        p -= 2;
        memcpy(p, DIGIT_PAIRS + low % 100 * 2, 2);
    }
    if (low >= 10) {
        p -= 2;
        memcpy(p, DIGIT_PAIRS + low * 2, 2);
    } else {
        *--p = (char)('0' + low);
    }
    while ((unsigned)(end - p) < width)
        *--p = '0';
    return p;
}

/* Room for any uint_text of a uint8_t width: 255 digits. */
#define NMEA_UINT_TEXT 255

/* An unsigned number in decimal, zero-padded to at least `width` digits. */
static void put_uint(nmea_writer *w, uint64_t v, unsigned width)
{
    char text[NMEA_UINT_TEXT], *end = text + sizeof text, *p;
    for (; width > NMEA_UINT_TEXT; width--)
        put_char(w, '0');
    p = uint_text(end, v, width);
    put_mem(w, p, (size_t)(end - p));
}

/* The NUL-terminated result, or 0 when it did not fit. */
static size_t writer_finish(nmea_writer *w)
{
    if (w->len < w->cap) {
        w->buf[w->len] = 0;
        return w->len;
    }
    if (w->cap)
        w->buf[0] = 0;
    return 0;
}

/* A character of a JSON string escaped `depth` times; `wide`: `c` is the low byte of a character
   above 0xFF, which the tools escape as \u00hh of that byte. */
static void put_escaped_char(nmea_writer *w, char c, bool wide, int depth)
{
    unsigned char u = (unsigned char)c;
    if (depth == 0) {
        put_char(w, c);
    } else if (!wide && (c == '"' || c == '\\')) {
        put_escaped_char(w, '\\', false, depth - 1);
        put_escaped_char(w, c, false, depth - 1);
    } else if (wide || !is_printable(c)) {
        put_escaped_char(w, '\\', false, depth - 1);
        put_escaped_char(w, 'u', false, depth - 1);
        put_escaped_char(w, '0', false, depth - 1);
        put_escaped_char(w, '0', false, depth - 1);
        put_escaped_char(w, HEX_LOWER[u >> 4], false, depth - 1);
        put_escaped_char(w, HEX_LOWER[u & 15], false, depth - 1);
    } else {
        put_escaped_char(w, c, false, depth - 1);
    }
}

/* A character of a JSON string, escaped `depth` times (a message holding a quoted text is
   itself escaped inside the JSON of an error: depth 2 for the text). */
static void put_escaped(nmea_writer *w, char c, int depth)
{
    put_escaped_char(w, c, false, depth);
}

static void put_escaped_mem(nmea_writer *w, const char *s, size_t n, int depth)
{
    size_t i;
    if (depth == 1) { /* the common case, without the recursion */
        for (i = 0; i < n; i++) {
            char c = s[i];
            if (is_printable(c) && c != '"' && c != '\\')
                put_char(w, c);
            else
                put_escaped(w, c, 1);
        }
        return;
    }
    for (i = 0; i < n; i++)
        put_escaped(w, s[i], depth);
}

#ifndef NMEA_NO_JSON
/* A JSON string of `t`, written inside text escaped `depth` times. */
static void put_json_str(nmea_writer *w, nmea_text t, int depth)
{
    put_escaped(w, '"', depth);
    put_escaped_mem(w, t.ptr, t.len, depth + 1);
    put_escaped(w, '"', depth);
}
#endif


/* ------------------------------------------------------------------------------------------ */
/* Errors */

static const char *const ERROR_KINDS[] = {
    "too_long", "not_a_sentence", "bad_checksum", "checksum_mismatch", "missing_checksum", "too_few_fields",
    "too_many_fields", "bad_field", "bad_json", "bad_value",
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
    fail(err, NMEA_ERR_TOO_LONG, "line is %n bytes, the limit is %n");
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
    const char *p = err->pattern ? err->pattern : "";
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
    fail(err, NMEA_ERR_BAD_FIELD, "expected %s, found %q");
    err->field = p->field;
    err->group = p->group;
    err->entry = p->entry;
    err->name = p->name;
    err->str[0] = p->expected;
    err->text = p->text;
}

/* A bad_field error kept as a problem. */
static void problem_of(nmea_problem *p, const nmea_error *err)
{
    p->field = (uint16_t)err->field;
    p->entry = (uint16_t)err->entry;
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

/* ------------------------------------------------------------------------------------------ */
/* Framing: a line split into start, address and fields, its checksum verified. */

typedef struct {
    nmea_text start;
    nmea_text address;
    nmea_text fields; /* the text after the address and its comma */
    size_t count;     /* number of fields */
    nmea_checksum_style checksum;
} nmea_frame;

/* The body of a sentence is read 8 bytes at a time as one 64-bit word (SWAR): each function
   below sets the high bit of every byte of the word that is (exactly) what it looks for. The
   order of the bytes in the word does not matter to any of them. */
#define BYTES_ONES UINT64_C(0x0101010101010101)
#define BYTES_HIGH UINT64_C(0x8080808080808080)
#define BYTES_LOW7 UINT64_C(0x7F7F7F7F7F7F7F7F)

/* The zero bytes (no carry crosses a byte, so there are no false positives). */
static inline uint64_t zero_bytes(uint64_t word)
{
    return ~(((word & BYTES_LOW7) + BYTES_LOW7) | word | BYTES_LOW7);
}

/* The bytes that end the body of a sentence: '*', and whatever is not printable ASCII (below
   0x20, 0x7F and above). */
static inline uint64_t body_end_bytes(uint64_t word)
{
    uint64_t low7 = word & BYTES_LOW7;
    return ((word | ~(low7 + 0x60 * BYTES_ONES) | (low7 + BYTES_ONES)) & BYTES_HIGH)
           | zero_bytes(word ^ ('*' * BYTES_ONES));
}

/* How many bytes a byte mask marks. */
static inline size_t count_bytes(uint64_t mask)
{
    return (size_t)(((mask >> 7) * BYTES_ONES) >> 56);
}

static bool ends_body(unsigned char c)
{
    return c < 0x20 || c > 0x7E || c == '*';
}

/* One pass over the line: the printable check, the checksum and the field count; with
   `require_checksum`, a sentence without a checksum (or with a bare '*') is refused. */
static bool frame_line(nmea_frame *f, const char *line, size_t len, bool require_checksum, nmea_error *err)
{
    size_t i, star = 0, comma = 0, commas = 0, body_end, words_end;
    unsigned sum = 0;
    int high = -1, low = -1; /* the checksum's hex digits */
    uint64_t word, words = 0;
    bool named = false, lower = false, upper = false;
    nmea_text sent;

    if (len > NMEA_MAX_LINE) {
        nmea_error_too_long(err, len);
        return false;
    }
    if (len == 0)
        return fail(err, NMEA_ERR_NOT_A_SENTENCE, "empty line");
    if (line[0] != '$' && line[0] != '!')
        return fail(err, NMEA_ERR_NOT_A_SENTENCE, "line does not start with '$' or '!'");
    if (len > 6 && line[6] == ',' && is_alnum(line[1]) && is_alnum(line[2]) && is_alnum(line[3])
        && is_alnum(line[4]) && is_alnum(line[5])) { /* the usual address: talker and sentence id */
        named = true;
        sum = (unsigned char)(line[1] ^ line[2] ^ line[3] ^ line[4] ^ line[5] ^ ',');
        commas = 1;
        comma = 6;
        i = 7;
    } else {
        for (i = 1; i < len && !ends_body((unsigned char)line[i]); i++) { /* the address */
            sum ^= (unsigned char)line[i];
            if (line[i] == ',') {
                commas = 1;
                comma = i++;
                break;
            }
        }
    }
    /* the fields, a word at a time up to the usual "*hh" at the end (the byte loop then finds
       where the body really ends) */
    words_end = len >= 3 && line[len - 3] == '*' ? len - 3 : len;
    for (; commas && i + 8 <= words_end; i += 8) {
        memcpy(&word, line + i, 8);
        if (body_end_bytes(word))
            break;
        words ^= word;
        commas += count_bytes(zero_bytes(word ^ (',' * BYTES_ONES)));
    }
    for (; i < len && !ends_body((unsigned char)line[i]); i++) { /* the rest of the body */
        sum ^= (unsigned char)line[i];
        commas += line[i] == ',';
    }
    words ^= words >> 32;
    words ^= words >> 16;
    words ^= words >> 8;
    sum ^= (unsigned char)words;
    if (i < len && line[i] == '*')
        for (star = i++; i < len && is_printable(line[i]); i++)
            continue;
    if (i < len) {
        fail(err, NMEA_ERR_NOT_A_SENTENCE, "byte 0x%x at offset %n is not printable ASCII");
        err->num[0] = (unsigned char)line[i];
        err->num[1] = i;
        return false;
    }
    body_end = star ? star : len;
    f->start = text_span(line, line + 1);
    f->address = text_span(line + 1, line + (comma ? comma : body_end));
    if (!named) { /* not yet known to be letters and digits */
        named = f->address.len > 0;
        for (i = 0; i < f->address.len && named; i++)
            named = is_alnum(f->address.ptr[i]);
    }
    f->checksum = NMEA_CHECKSUM_NONE;
    if (star && star + 1 == len) { /* a bare '*' leaves the checksum out */
        f->checksum = NMEA_CHECKSUM_EMPTY;
    } else if (star) {
        sent = text_span(line + star + 1, line + len);
        if (sent.len == 2) {
            high = hex_value(sent.ptr[0]);
            low = hex_value(sent.ptr[1]);
            lower = (sent.ptr[0] >= 'a' && sent.ptr[0] <= 'f') || (sent.ptr[1] >= 'a' && sent.ptr[1] <= 'f');
            upper = (sent.ptr[0] >= 'A' && sent.ptr[0] <= 'F') || (sent.ptr[1] >= 'A' && sent.ptr[1] <= 'F');
        }
        if (high < 0 || low < 0 || (lower && upper)) {
            fail(err, NMEA_ERR_BAD_CHECKSUM, "checksum %q is not two hex digits of one letter case");
            err->text = sent;
            if (named)
                set_address(err, f->address, NULL);
            return false;
        }
        if ((unsigned)(high * 16 + low) != sum) {
            fail(err, NMEA_ERR_CHECKSUM_MISMATCH, "checksum is %t, computed %X");
            err->text = sent;
            err->num[0] = sum;
            if (named)
                set_address(err, f->address, NULL);
            return false;
        }
        f->checksum = lower ? NMEA_CHECKSUM_LOWER : NMEA_CHECKSUM_UPPER;
    }
    if (!named) {
        fail(err, NMEA_ERR_NOT_A_SENTENCE, "address %q is not letters and digits");
        err->text = f->address;
        return false;
    }
    if (require_checksum && (f->checksum == NMEA_CHECKSUM_NONE || f->checksum == NMEA_CHECKSUM_EMPTY)) {
        fail(err, NMEA_ERR_MISSING_CHECKSUM, "the sentence has no checksum");
        set_address(err, f->address, NULL);
        return false;
    }
    f->count = commas;
    f->fields = commas ? text_span(line + comma + 1, line + body_end) : text_span(line + body_end, line + body_end);
    return true;
}

/* A talker ID and a 3-letter sentence formatter: '$' (or '!', an encapsulation sentence such as
   AIS VDM), 5 characters, not proprietary ('P...'). */
static bool is_standard_address(const nmea_frame *f)
{
    return f->start.len == 1 && (f->start.ptr[0] == '$' || f->start.ptr[0] == '!') && f->address.len == 5 &&
           f->address.ptr[0] != 'P';
}

/* A text command (ComNav: words separated by single spaces, no '$', no checksum): the first
   word is the address, the others are the fields. */
static bool text_frame(nmea_frame *f, const char *line, size_t len, nmea_error *err)
{
    size_t i, space = 0, spaces = 0;

    if (len > NMEA_MAX_LINE) {
        nmea_error_too_long(err, len);
        return false;
    }
    for (i = 0; i < len; i++) {
        if (!is_printable(line[i])) {
            fail(err, NMEA_ERR_NOT_A_SENTENCE, "byte 0x%x at offset %n is not printable ASCII");
            err->num[0] = (unsigned char)line[i];
            err->num[1] = i;
            return false;
        }
        if (line[i] == ' ' && !spaces++)
            space = i;
    }
    f->start = text_span(line, line);
    f->address = text_span(line, line + (spaces ? space : len));
    f->count = spaces;
    f->fields = spaces ? text_span(line + space + 1, line + len) : text_span(line + len, line + len);
    f->checksum = NMEA_CHECKSUM_NONE;
    return true;
}

/* The command word of a possible text command: the text before the first space. */
static nmea_text first_word(const char *line, size_t len)
{
    const char *space = len ? memchr(line, ' ', len) : NULL;
    return text_span(line, space ? space : line + len);
}

/* Whether `word` in upper case is the command word `upper` (the upper case of Latin-1 0xDF,
   the sharp s, being "SS" as in the Python reference). */
static bool word_is(nmea_text word, const char *upper)
{
    size_t i;
    for (i = 0; i < word.len; i++) {
        if ((unsigned char)word.ptr[i] == 0xDF) {
            if (upper[0] != 'S' || upper[1] != 'S')
                return false;
            upper += 2;
        } else if (!*upper || ascii_upper(word.ptr[i]) != *upper++) {
            return false;
        }
    }
    return *upper == 0;
}

/* ------------------------------------------------------------------------------------------ */
/* Stream framing */

/* The bytes that end a line (CR, LF) or start a new one ('$', '!'). */
static const unsigned char LINE_BOUNDARY[256] = {['\r'] = 1, ['\n'] = 1, ['$'] = 2, ['!'] = 2};

void nmea_framer_init(nmea_framer *f)
{
    f->length = 0;
}

/* Adds bytes to the line being assembled (only its first NMEA_MAX_LINE bytes are kept). */
static void framer_keep(nmea_framer *f, const char *p, size_t n)
{
    if (f->length < NMEA_MAX_LINE)
        memcpy(f->line + f->length, p, n < NMEA_MAX_LINE - f->length ? n : NMEA_MAX_LINE - f->length);
    f->length += n;
}

bool nmea_framer_push(nmea_framer *f, const char **data, size_t *len, nmea_framed *out)
{
    const char *p = *data, *end, *q;
    if (*len == 0)
        return false;
    end = p + *len;
    if (f->length == 0) {
        while (p < end && LINE_BOUNDARY[(unsigned char)*p] == 1) /* empty lines */
            p++;
        if (p == end) {
            *data = end;
            *len = 0;
            return false;
        }
        /* a line starts at p: one that ends in this chunk is handed on where it lies */
        for (q = p + 1; q < end && !LINE_BOUNDARY[(unsigned char)*q]; q++)
            continue;
        if (q < end) {
            out->ptr = (size_t)(q - p) <= NMEA_MAX_LINE ? p : NULL;
            out->len = (size_t)(q - p);
            q += LINE_BOUNDARY[(unsigned char)*q] == 1; /* a '$' or '!' stays for the next line */
            *data = q;
            *len = (size_t)(end - q);
            return true;
        }
    } else {
        for (q = p; q < end && !LINE_BOUNDARY[(unsigned char)*q]; q++)
            continue;
        framer_keep(f, p, (size_t)(q - p));
        if (q < end) {
            out->ptr = f->length <= NMEA_MAX_LINE ? f->line : NULL;
            out->len = f->length;
            f->length = 0;
            q += LINE_BOUNDARY[(unsigned char)*q] == 1;
            *data = q;
            *len = (size_t)(end - q);
            return true;
        }
        p = q;
    }
    framer_keep(f, p, (size_t)(end - p));
    *data = end;
    *len = 0;
    return false;
}

bool nmea_framer_end(nmea_framer *f, nmea_framed *out)
{
    if (f->length == 0)
        return false;
    out->ptr = f->length <= NMEA_MAX_LINE ? f->line : NULL;
    out->len = f->length;
    f->length = 0;
    return true;
}

/* A known sentence starts with '$' (or '!', an encapsulation sentence), its talker and its
   sentence id; the checksum covers all but the start. Each field writes its comma, end_sentence
   the checksum. */
NMEA_INTERNAL void begin_sentence(nmea_writer *w, char start, nmea_text talker, const char *sentence,
                                  const nmea_problems *problems)
{
    w->problems = problems;
    w->field = 0;
    put_char(w, start);
    start_sum(w);
    put_text(w, talker);
    put_str(w, sentence);
}

static void end_sentence(nmea_writer *w, nmea_checksum_style style)
{
    unsigned char sum;
    stop_sum(w);
    sum = w->sum;
    w->problems = NULL;
    if (style == NMEA_CHECKSUM_NONE)
        return;
    put_char(w, '*');
    if (style == NMEA_CHECKSUM_EMPTY)
        return;
    put_char(w, (style == NMEA_CHECKSUM_LOWER ? HEX_LOWER : HEX_UPPER)[sum >> 4]);
    put_char(w, (style == NMEA_CHECKSUM_LOWER ? HEX_LOWER : HEX_UPPER)[sum & 15]);
}

/* A text command: the command word and each field after a space (the put_ functions write
   w->sep). Written back exactly as received when its words still match ignoring case. */
NMEA_INTERNAL void begin_text(nmea_writer *w, const char *address, nmea_text as_received,
                              const nmea_problems *problems)
{
    w->problems = problems;
    w->field = 0;
    w->sep = ' ';
    w->start = w->len;
    w->match = as_received.ptr;
    w->quick_cap = 0;
    w->match_len = as_received.len;
    w->match_pos = 0;
    w->matched = as_received.ptr != NULL;
    if (w->matched)
        start_sum(w);
    put_str(w, address);
}

NMEA_INTERNAL void end_text(nmea_writer *w)
{
    size_t i;
    stop_sum(w);
    w->matched = w->matched && w->match_pos == w->match_len;
    for (i = 0; w->matched && i < w->match_len && w->start + i < w->cap; i++)
        w->buf[w->start + i] = w->match[i];
    w->match = NULL;
    w->quick_cap = w->cap;
    w->sep = ',';
    w->problems = NULL;
}

nmea_text nmea_generic_field(const nmea_generic *g, size_t index)
{
    const char *p = g->fields.ptr, *end = p + g->fields.len;
    const char *comma;
    if (index >= g->field_count)
        return text_span(end, end);
    for (;;) {
        comma = p;
        while (comma < end && *comma != ',')
            comma++;
        if (index-- == 0)
            return text_span(p, comma);
        p = comma < end ? comma + 1 : end;
    }
}

static void write_generic(nmea_writer *w, const nmea_generic *g)
{
    put_text(w, g->start);
    start_sum(w);
    put_text(w, g->address);
    if (g->field_count) {
        put_char(w, ',');
        put_text(w, g->fields);
    }
    end_sentence(w, g->checksum);
}

/* ------------------------------------------------------------------------------------------ */
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

/* [+-]digits[.digits] (no point for an integer), at most NMEA_MAX_DIGITS digits. */
static bool parse_number(nmea_text t, bool integer, nmea_number *out)
{
    const char *p = t.ptr, *end = t.ptr + t.len;
    size_t whole, frac = 0;
    int64_t digits = 0;
    char sign = 0;
    bool point = false;

    if (p < end && (*p == '+' || *p == '-'))
        sign = *p++;
    whole = take_digits(&p, end, &digits, NMEA_MAX_DIGITS);
    if (p < end && *p == '.' && !integer) {
        point = true;
        p++;
        frac = take_digits(&p, end, &digits, NMEA_MAX_DIGITS - whole);
    }
    if (p != end || whole + frac == 0)
        return false;
    out->digits = digits;
    out->scale = (uint8_t)frac;
    out->width = (uint8_t)whole;
    out->sign = sign;
    out->point = point;
    out->present = true;
    return true;
}

/* Compares a * 10^-as with b * 10^-bs (both signed): -1, 0 or 1. */
static int compare_fixed(int64_t a, unsigned as, int64_t b, unsigned bs)
{
    int64_t wa, wb, fa, fb;
    if (as == bs) /* the common case: an integer against integer bounds */
        return a < b ? -1 : a > b;
    if (as > bs && b > -POW10[NMEA_MAX_DIGITS - (as - bs)] && b < POW10[NMEA_MAX_DIGITS - (as - bs)]) {
        b *= POW10[as - bs];
        return a < b ? -1 : a > b;
    }
    if (as < bs && a > -POW10[NMEA_MAX_DIGITS - (bs - as)] && a < POW10[NMEA_MAX_DIGITS - (bs - as)]) {
        a *= POW10[bs - as];
        return a < b ? -1 : a > b;
    }
    /* whole parts first, then the fractions scaled to NMEA_MAX_DIGITS digits */
    wa = a / POW10[as];
    wb = b / POW10[bs];
    fa = (a % POW10[as]) * POW10[NMEA_MAX_DIGITS - as];
    fb = (b % POW10[bs]) * POW10[NMEA_MAX_DIGITS - bs];
    if (wa != wb)
        return wa < wb ? -1 : 1;
    return fa < fb ? -1 : fa > fb;
}

static inline bool in_range(const nmea_number *n, const nmea_range *range)
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
    whole = magnitude / (uint64_t)POW10[scale];
    n.digits = (int64_t)magnitude;
    n.scale = (uint8_t)scale;
    for (n.width = 1; whole >= 10; whole /= 10)
        n.width++;
    n.sign = value < 0 ? '-' : 0;
    n.point = scale > 0;
    n.present = true;
    return n;
}

static bool parse_hex(nmea_text t, nmea_hex *out)
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
static bool parse_time(nmea_text t, nmea_time *out)
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

static bool parse_date(nmea_text t, nmea_date *out)
{
    return t.len == 6 && all_digits(t.ptr, 6) && date_of(t.ptr, out);
}

/* A coordinate's value read as `whole` digits before the point (worth `whole_value`) and `frac`
   after it (the minutes, fraction included, worth `minutes`): checked and stored in `out`. */
NMEA_HOT bool coordinate_of(uint64_t whole_value, size_t whole, uint64_t minutes, size_t frac, bool point,
                            unsigned max_degree_digits, unsigned max_degrees, nmea_coordinate *out)
{
    if (whole < 2 || whole > 2 + max_degree_digits || frac > NMEA_MAX_DIGITS - 2)
        return false;
    if (whole_value / 100 > max_degrees || minutes > (uint64_t)(60 * POW10[frac]))
        return false;
    out->degrees = (uint16_t)(whole_value / 100);
    out->degree_digits = (uint8_t)(whole - 2);
    out->minutes.digits = (int64_t)minutes;
    out->minutes.scale = (uint8_t)frac;
    out->minutes.width = 2;
    out->minutes.sign = 0;
    out->minutes.point = point;
    out->minutes.present = true;
    out->present = true;
    return true;
}

/* ddmm.mmmm (latitude) or dddmm.mmmm (longitude): the two digits before the point are whole
   minutes, the digits before them degrees. */
static bool parse_coordinate(nmea_text t, unsigned max_degree_digits, unsigned max_degrees, nmea_coordinate *out)
{
    const char *p = t.ptr, *end = t.ptr + t.len, *point = NULL;
    uint64_t whole_value = 0, minutes; /* unsigned: digits too many for them are refused below */
    size_t whole, frac = 0;

    for (; p < end && is_digit(*p); p++)
        whole_value = whole_value * 10 + (uint64_t)(*p - '0');
    whole = (size_t)(p - t.ptr);
    minutes = whole_value % 100;
    if (p < end && *p == '.') {
        for (point = p++; p < end && is_digit(*p); p++)
            minutes = minutes * 10 + (uint64_t)(*p - '0');
        frac = (size_t)(p - point - 1);
    }
    return p == end && coordinate_of(whole_value, whole, minutes, frac, point != NULL, max_degree_digits, max_degrees,
                                     out);
}

/* Whether a code the table does not know is still well formed for it: the same length range
   and character class as the known codes. */
static bool is_code_like(const nmea_enum_def *def, const char *p, size_t n, size_t min_len, size_t max_len)
{
    size_t i;
    if (n < min_len || n > max_len)
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
static int enum_find_upper(const nmea_enum_def *def, nmea_text t)
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

/* ------------------------------------------------------------------------------------------ */
/* Reading the fields of a layout: a cursor over the comma-separated fields, which knows the
   address and the field being read for the errors. */

/* The fields of a line (or of decode's JSON) for a layout to read, and the address its errors
   name: `address` followed by `suffix` (a standard sentence: the talker and the sentence id). */
typedef struct {
    nmea_text address;
    const char *suffix;
    nmea_text fields;
    size_t count;
    char sep;                     /* between fields: ',' or ' ' (the words of a text command) */
    bool ignore_case;             /* a text command: keywords and enum codes match ignoring case */
    nmea_checksum_style checksum;
    nmea_text line;               /* a text command: the command as received */
    uint16_t blank[NMEA_MAX_PROBLEMS]; /* lenient parsing: the wire fields read as empty */
    unsigned blanks;
} nmea_wire;

typedef struct {
    const char *next;
    const char *end;
    unsigned index; /* 1-based wire index of the field read last */
    nmea_text address;
    const char *suffix;
    const char *sentence;
    const char *group;
    unsigned entry;
    char sep;
    bool ignore_case;
    const uint16_t *blank;
    unsigned blanks;
    nmea_error *err;
} nmea_reader;

static void reader_start(nmea_reader *r, const nmea_wire *wire, const char *sentence, nmea_error *err)
{
    r->next = wire->fields.ptr;
    r->end = wire->fields.ptr + wire->fields.len;
    r->index = 0;
    r->address = wire->address;
    r->suffix = wire->suffix;
    r->sentence = sentence;
    r->group = NULL;
    r->entry = 0;
    r->sep = wire->sep;
    r->ignore_case = wire->ignore_case;
    r->blank = wire->blank;
    r->blanks = wire->blanks;
    r->err = err;
}

/* Zeroes the `size` first bytes of a layout struct before it is read, with the C library's
   memset: the size is read back from a volatile so that the compiler cannot see it is a
   constant of a few hundred bytes, which it would inline as `rep stos`, slow to start. */
NMEA_OUTLINE void clear_layout(void *s, size_t size)
{
    volatile size_t unknown = size;
    memset(s, 0, unknown);
}

/* Whether lenient parsing reads wire field `index` (1-based) as empty. */
NMEA_RARE bool is_blank(const uint16_t *blank, unsigned blanks, unsigned index)
{
    unsigned i;
    for (i = 0; i < blanks; i++)
        if (blank[i] == index)
            return true;
    return false;
}

/* From now on the fields read belong to entry `index` (0-based) of `group` (NULL: none). */
NMEA_INTERNAL void reader_entry(nmea_reader *r, const char *group, size_t index)
{
    r->group = group;
    r->entry = (unsigned)index + 1;
}

static inline nmea_text next_field(nmea_reader *r)
{
    const char *p = r->next, *q = p, *end = r->end; /* (locals: the bytes read could alias r) */
    char sep = r->sep;
    nmea_text t;
    r->index++;
    while (q < end && *q != sep)
        q++;
    t = text_span(p, q);
    r->next = q < end ? q + 1 : q;
    if (r->blanks && is_blank(r->blank, r->blanks, r->index))
        t.len = 0;
    return t;
}

static bool count_error(nmea_reader *r, nmea_error_kind kind, const char *pattern, size_t n, size_t m)
{
    fail(r->err, kind, pattern);
    set_address(r->err, r->address, r->suffix);
    r->err->str[0] = r->sentence;
    r->err->num[0] = n;
    r->err->num[1] = m;
    return false;
}

static bool too_few(nmea_reader *r, size_t need, size_t found)
{
    return count_error(r, NMEA_ERR_TOO_FEW_FIELDS, "%s needs at least %n fields, found %n", need, found);
}

static bool too_many(nmea_reader *r, size_t limit, size_t found)
{
    return count_error(r, NMEA_ERR_TOO_MANY_FIELDS, "%s takes at most %n fields, found %n", limit, found);
}

/* A layout without a repeated group: `fixed` required fields, `max` in all. Sets `optional` to
   the number of optional trailing wire fields present. */
/* The wire of a framed line: a standard sentence's address is its talker followed by `suffix`
   (its 3-character sentence id); a text command (`line`, as received) has words separated by
   spaces. */
static void wire_of(nmea_wire *wire, const nmea_frame *f, const char *suffix, const char *line)
{
    wire->address = suffix ? text_span(f->address.ptr, f->address.ptr + f->address.len - 3) : f->address;
    wire->suffix = suffix;
    wire->fields = f->fields;
    wire->count = f->count;
    wire->sep = line ? ' ' : ',';
    wire->ignore_case = line != NULL;
    wire->checksum = f->checksum;
    wire->line = line ? text_span(line, f->fields.ptr + f->fields.len) : nmea_text_of(NULL);
    wire->blanks = 0;
}

/* For nmea_build_*: the sentence just written to w (which must hold it, its CR LF and a NUL),
   framed again as a receiver frames it. */
NMEA_INTERNAL bool build_wire(nmea_writer *w, bool text, nmea_wire *wire, nmea_error *err)
{
    nmea_frame f;
    if (w->len + 2 >= w->cap) {
        fail(err, NMEA_ERR_TOO_LONG, "the sentence, its CR LF and a NUL need %n bytes, the buffer holds %n");
        err->num[0] = w->len + 3;
        err->num[1] = w->cap;
        w->len = w->cap; /* nothing of it is kept */
        return false;
    }
    if (!(text ? text_frame(&f, w->buf, w->len, err) : frame_line(&f, w->buf, w->len, false, err)))
        return false;
    wire_of(wire, &f, NULL, text ? w->buf : NULL);
    return true;
}

/* A refused sentence stays in the buffer (the error points into it); one too long is not kept. */
NMEA_INTERNAL size_t build_failed(nmea_writer *w)
{
    writer_finish(w);
    return 0;
}

NMEA_INTERNAL size_t build_end(nmea_writer *w)
{
    put_char(w, '\r');
    put_char(w, '\n');
    return writer_finish(w);
}

NMEA_INTERNAL inline bool read_count(nmea_reader *r, size_t count, size_t fixed, size_t max, size_t *optional)
{
    *optional = 0; /* (set first: once inlined, gcc -O1 cannot tell it is read only on success) */
    if (count < fixed)
        return too_few(r, fixed, count);
    if (count > max)
        return too_many(r, max, count);
    *optional = count - fixed;
    return true;
}

/* A layout with a repeated group of `width` wire fields, `min` to `max` times, and `fixed`
   required fields besides: how many times it occurs and how many optional wire fields follow. */
NMEA_INTERNAL inline bool read_group_count(nmea_reader *r, size_t count, const char *group, size_t fixed, size_t width,
                                           size_t min, size_t max, size_t optional_max, size_t *repeats, size_t *optional)
{
    size_t rest, extra;
    *repeats = 0; /* (set first: once inlined, gcc -O1 cannot tell they are read only on success) */
    *optional = 0;
    if (count < fixed + min * width)
        return too_few(r, fixed + min * width, count);
    rest = count - fixed;
    *repeats = rest / width < max ? rest / width : max;
    extra = rest - *repeats * width;
    if (extra > optional_max) {
        if (*repeats == max)
            return too_many(r, fixed + max * width + optional_max, count);
        count_error(r, NMEA_ERR_TOO_FEW_FIELDS, "%s %s entries take %n fields each, %n left over", width, extra);
        r->err->str[1] = group;
        return false;
    }
    *optional = extra;
    return true;
}

static bool bad_field(nmea_reader *r, unsigned index, const char *name, const char *expected, nmea_text text)
{
    nmea_error *err = r->err;
    fail(err, NMEA_ERR_BAD_FIELD, "expected %s, found %q");
    set_address(err, r->address, r->suffix);
    err->field = index;
    err->group = r->group;
    err->entry = r->entry;
    err->name = name;
    err->str[0] = expected;
    err->text = text;
    return false;
}

/* The general reading of an integer or decimal field. */
NMEA_RARE bool read_number(nmea_reader *r, nmea_number *out, const char *name, const char *expected,
                           const nmea_range *range, bool integer)
{
    nmea_text t = next_field(r);
    if (t.len && !(parse_number(t, integer, out) && in_range(out, range)))
        return bad_field(r, r->index, name, expected, t);
    return true;
}

/* The common case of read_number, in the one pass that finds the end of the field: an empty
   field, or digits with (`integer` false) at most one point, NMEA_MAX_DIGITS digits in all, in
   `range`. Anything else (a sign, more digits, not a number, out of range, a field lenient
   parsing reads as empty) is left to read_number: returns false without having read it. */
NMEA_HOT bool quick_number(nmea_reader *r, nmea_number *out, const nmea_range *range, bool integer)
{
    const char *p = r->next, *end = r->end, *point = NULL;
    uint64_t digits = 0; /* unsigned: a run too long for it is refused below, not undefined */
    unsigned digit;      /* unsigned: a byte below '0' wraps to a large value */
    size_t whole, count;
    nmea_number n;

    if (r->blanks)
        return false;
    for (; p < end && (digit = (unsigned)(unsigned char)*p - '0') < 10; p++)
        digits = digits * 10 + digit;
    whole = (size_t)(p - r->next);
    if (!integer && p < end && *p == '.')
        for (point = p++; p < end && (digit = (unsigned)(unsigned char)*p - '0') < 10; p++)
            digits = digits * 10 + digit;
    count = (size_t)(p - r->next) - (point != NULL); /* digits before and after the point */
    if ((p < end && *p != r->sep) || count > NMEA_MAX_DIGITS || (point && count == 0))
        return false;
    if (count) {
        n.digits = (int64_t)digits;
        n.scale = (uint8_t)(count - whole);
        n.width = (uint8_t)whole;
        n.sign = 0;
        n.point = point != NULL;
        n.present = true;
        if (!in_range(&n, range))
            return false;
        *out = n;
    }
    r->index++;
    r->next = p < end ? p + 1 : p;
    return true;
}

NMEA_HOT bool read_integer(nmea_reader *r, nmea_number *out, const char *name, const char *expected,
                           const nmea_range *range)
{
    return quick_number(r, out, range, true) || read_number(r, out, name, expected, range, true);
}

NMEA_HOT bool read_decimal(nmea_reader *r, nmea_number *out, const char *name, const char *expected,
                           const nmea_range *range)
{
    return quick_number(r, out, range, false) || read_number(r, out, name, expected, range, false);
}

NMEA_INTERNAL bool read_hex(nmea_reader *r, nmea_hex *out, const char *name, const char *expected)
{
    nmea_text t = next_field(r);
    if (t.len && !parse_hex(t, out))
        return bad_field(r, r->index, name, expected, t);
    return true;
}

NMEA_INTERNAL bool read_time(nmea_reader *r, nmea_time *out, const char *name, const char *expected)
{
    nmea_text t = next_field(r);
    if (t.len && !parse_time(t, out))
        return bad_field(r, r->index, name, expected, t);
    return true;
}

NMEA_INTERNAL bool read_date(nmea_reader *r, nmea_date *out, const char *name, const char *expected)
{
    nmea_text t = next_field(r);
    if (t.len && !parse_date(t, out))
        return bad_field(r, r->index, name, expected, t);
    return true;
}

/* A value field and a hemisphere field, both empty or both set. */
static bool read_coordinate(nmea_reader *r, nmea_coordinate *out, const char *name, const char *expected,
                            const char *hemisphere_expected, const char *hemispheres, unsigned max_degree_digits,
                            unsigned max_degrees)
{
    nmea_text value = next_field(r);
    nmea_text hemisphere = next_field(r);
    if (!value.len) {
        if (hemisphere.len)
            return bad_field(r, r->index - 1, name, expected, value);
        return true;
    }
    if (!parse_coordinate(value, max_degree_digits, max_degrees, out))
        return bad_field(r, r->index - 1, name, expected, value);
    if (hemisphere.len != 1 || (hemisphere.ptr[0] != hemispheres[0] && hemisphere.ptr[0] != hemispheres[1])) {
        out->present = false;
        return bad_field(r, r->index, name, hemisphere_expected, hemisphere);
    }
    out->hemisphere = hemisphere.ptr[0];
    return true;
}

NMEA_INTERNAL bool read_latitude(nmea_reader *r, nmea_coordinate *out, const char *name, const char *expected,
                                 const char *hemisphere_expected)
{
    return read_coordinate(r, out, name, expected, hemisphere_expected, "NS", 2, 90);
}

NMEA_INTERNAL bool read_longitude(nmea_reader *r, nmea_coordinate *out, const char *name, const char *expected,
                                  const char *hemisphere_expected)
{
    return read_coordinate(r, out, name, expected, hemisphere_expected, "EW", 3, 180);
}

NMEA_INTERNAL bool read_char(nmea_reader *r, char *out, const char *name, const char *expected)
{
    nmea_text t = next_field(r);
    if (t.len > 1)
        return bad_field(r, r->index, name, expected, t);
    *out = t.len ? t.ptr[0] : 0;
    return true;
}

NMEA_INTERNAL bool read_literal(nmea_reader *r, bool *out, const char *name, const char *expected, const char *literal)
{
    nmea_text t = next_field(r);
    if (t.len && !text_is(t, literal))
        return bad_field(r, r->index, name, expected, t);
    *out = t.len > 0;
    return true;
}

/* A fixed word that must be there (it picks the layout); in a text command ignoring case. */
NMEA_INTERNAL bool read_keyword(nmea_reader *r, const char *name, const char *expected, const char *keyword)
{
    nmea_text t = next_field(r);
    if (!text_is(t, keyword) && !(r->ignore_case && upper_is(t, keyword)))
        return bad_field(r, r->index, name, expected, t);
    return true;
}

NMEA_INTERNAL bool read_text(nmea_reader *r, nmea_text *out, const char *name, const char *expected, size_t max_length)
{
    nmea_text t = next_field(r);
    if (max_length && t.len > max_length)
        return bad_field(r, r->index, name, expected, t);
    *out = t;
    return true;
}

/* A known code, or a well-formed unknown one (kept in `code`). */
NMEA_INTERNAL bool read_enum(nmea_reader *r, nmea_enum *out, const char *name, const char *expected,
                             const nmea_enum_def *def)
{
    nmea_text t = next_field(r);
    size_t i;
    if (!t.len)
        return true;
    out->value = r->ignore_case ? enum_find_upper(def, t) : enum_find(def, t.ptr, t.len);
    if (out->value == NMEA_UNKNOWN_CODE && !is_code_like(def, t.ptr, t.len, def->min_len, def->max_len))
        return bad_field(r, r->index, name, expected, t);
    for (i = 0; i < t.len; i++) /* t.len <= max_len <= NMEA_CODE_MAX; a code is a character or two */
        out->code[i] = t.ptr[i];
    out->code[t.len] = 0;
    out->present = true;
    return true;
}

/* A run of one-character codes (GNS mode "ANNN"), kept as text. */
NMEA_INTERNAL bool read_enum_chars(nmea_reader *r, nmea_text *out, const char *name, const char *expected,
                                   const nmea_enum_def *def, size_t max_length)
{
    nmea_text t = next_field(r);
    size_t i;
    if (max_length && t.len > max_length)
        return bad_field(r, r->index, name, expected, t);
    for (i = 0; i < t.len; i++)
        if (enum_find(def, t.ptr + i, 1) == NMEA_UNKNOWN_CODE && !is_code_like(def, t.ptr + i, 1, 1, 1))
            return bad_field(r, r->index, name, expected, t);
    *out = t;
    return true;
}

/* ------------------------------------------------------------------------------------------ */
/* The fast path: a sentence in its usual form, read in one pass without the bookkeeping errors
   need. nmea_parse_ex tries it first; whatever it is not sure of (any field it cannot read, a
   field count that fits no layout, an unusual frame) it leaves to the general path above, which
   then reads the line from the start and finds the error. It accepts a subset of what the
   general path accepts and fills the struct exactly as the general path would: a build with
   NMEA_TEST_HOOKS checks that on every line it is given (nmea_parse_general). */

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
   false) at most one point, NMEA_MAX_DIGITS digits in all, in `range`. This general form takes
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
    if ((*q != ',' && *q != '*') || count > NMEA_MAX_DIGITS || (count == 0 && (point || n.sign)))
        return NULL;
    if (count) {
        n.digits = (int64_t)digits;
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
    if ((*q != ',' && *q != '*') || count > NMEA_MAX_DIGITS)
        return false;
    n.digits = (int64_t)digits;
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
    uint64_t whole_value = 0, minutes; /* unsigned: digits too many for them are refused below */
    unsigned digit;                    /* unsigned: a byte below '0' wraps to a large value */
    size_t whole, frac = 0;

    for (; (digit = (unsigned)(unsigned char)*q - '0') < 10; q++)
        whole_value = whole_value * 10 + digit;
    whole = (size_t)(q - start);
    minutes = whole_value % 100;
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

/* ------------------------------------------------------------------------------------------ */
/* Writing fields back: each writes its comma and its text (nothing for an empty field). */

/* The text of a field lenient parsing left empty, in its place (the last problem naming it). */
NMEA_RARE bool put_problem(nmea_writer *w)
{
    const nmea_problem *found = NULL;
    size_t i;
    for (i = 0; i < w->problems->count && i < NMEA_MAX_PROBLEMS; i++)
        if (w->problems->list[i].field == w->field)
            found = &w->problems->list[i];
    if (found)
        put_text(w, found->text);
    return found != NULL;
}

/* The separator before the next wire field; true when that field is a problem, whose text as
   received has then been written in place of the field's own. */
static inline bool put_sep(nmea_writer *w)
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
        v /= (uint64_t)POW10[n->scale];
    }
    if (n->width)
        p = uint_text(p, v, n->width);
    if (n->sign)
        *--p = n->sign;
    put_mem(w, p, (size_t)(end - p));
}

/* The number of decimal digits of v (one for 0). */
static inline unsigned digit_count(uint64_t v)
{
    unsigned count = 1;
    while (count <= NMEA_MAX_DIGITS && v >= (uint64_t)POW10[count])
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
static inline void number_text(nmea_writer *w, const nmea_number *n)
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

/* ------------------------------------------------------------------------------------------ */
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
        if (style != NMEA_CHECKSUM_EMPTY) {
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
    if (n->digits < 0 || count > NMEA_MAX_DIGITS || v >= (uint64_t)POW10[count] || (n->scale && !n->point))
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
            if (t->fraction >= (uint64_t)POW10[t->fraction_digits])
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
        if (c->degree_digits > 3 || c->degrees > 999 || (c->degree_digits && c->degrees >= POW10[c->degree_digits]))
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

#ifndef NMEA_NO_JSON
static void put_json_cstr(nmea_writer *w, const char *s)
{
    put_json_str(w, nmea_text_of(s), 0);
}

/* ------------------------------------------------------------------------------------------ */
/* The fields as JSON: the lossless texts, or (values) the decoded values. Each writes
   [,]"key": (no key inside an array) and the value. Left out by -DNMEA_NO_JSON, with the JSON
   reader below: the tools need them, a program that only parses and writes sentences does not. */

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
    uint64_t unit = (uint64_t)POW10[n->scale <= NMEA_MAX_DIGITS ? n->scale : 0];
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
    put_char(w, (style == NMEA_CHECKSUM_LOWER ? HEX_LOWER : HEX_UPPER)[sum >> 4]);
    put_char(w, (style == NMEA_CHECKSUM_LOWER ? HEX_LOWER : HEX_UPPER)[sum & 15]);
    put_str(w, "\"}");
}

/* ,"problems":[...]: each field lenient parsing left empty, with its text and why. */
static void json_problems(nmea_writer *w, const nmea_problems *problems)
{
    nmea_error err;
    size_t i;
    put_str(w, ",\"problems\":[");
    for (i = 0; i < problems->count && i < NMEA_MAX_PROBLEMS; i++) {
        problem_error(&problems->list[i], &err);
        put_str(w, i ? ",{\"field\":" : "{\"field\":");
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
    if (problems && problems->count)
        json_problems(w, problems);
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
    json_checksum(w, sum.sum, g->checksum);
}

/* ------------------------------------------------------------------------------------------ */
/* Reading JSON (the `encode` direction): a validator for the whole text, then lookups that
   walk the validated text again. A value is the span [p, end) of its text. */

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

/* Past the string starting at p (at its quote); NULL when it is not a valid string. */
static const char *json_string_end(const char *p, const char *end)
{
    long cp;
    p++;
    while (json_char_at(&p, end, &cp))
        continue;
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
    while (json_char_at(&p, end, &cp)) {
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
   lower case (when the text has a letter from a to z) or upper case. */
static bool json_checksum_style(nmea_json root, nmea_checksum_style *style, nmea_error *err)
{
    nmea_json v;
    const char *p;
    long cp;
    if (!json_require(root, "checksum", &v, err))
        return false;
    if (json_is_null(v)) {
        *style = NMEA_CHECKSUM_NONE;
        return true;
    }
    if (!json_is(v, '"'))
        return bad_json(err, "\"%s\" is not a string or null", "checksum");
    *style = v.end - v.p == 2 ? NMEA_CHECKSUM_EMPTY : NMEA_CHECKSUM_UPPER;
    for (p = v.p + 1; json_char_at(&p, v.end, &cp);)
        if (cp >= 'a' && cp <= 'z')
            *style = NMEA_CHECKSUM_LOWER;
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

/* Whether a line of decode's output is a JSON object whose "ok" is false (encode skips it). */
bool nmea_json_is_failure(const char *json, size_t len)
{
    nmea_json root, ok;
    return json_parse(json, len, &root) && json_member(root, "ok", &ok) && ok.end - ok.p == 5
        && memcmp(ok.p, "false", 5) == 0;
}
#endif /* NMEA_NO_JSON */

#ifndef NMEA_NO_TABLES
/* ------------------------------------------------------------------------------------------ */
/* Configuration parameter tables: the wire text of a value (Parameter.encode of the Python
   runtime). */

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
    param_refuse(p, "parameter %n (%s) is written as %s", err);
    err->str[1] = (unsigned)p->encoding < 4 ? NAMES[p->encoding] : "?";
    return false;
}

/* value * 10^-scale within the parameter's range. */
static bool param_in_range(const nmea_parameter *p, int64_t value, unsigned scale, nmea_error *err)
{
    if (p->range.has_min && compare_fixed(value, scale, p->range.min, p->range.min_scale) < 0)
        return param_refuse(p, "parameter %n (%s): the value is below its minimum", err);
    if (p->range.has_max && compare_fixed(value, scale, p->range.max, p->range.max_scale) > 0)
        return param_refuse(p, "parameter %n (%s): the value is above its maximum", err);
    return true;
}

static size_t param_finish(nmea_writer *w, nmea_error *err)
{
    size_t n = writer_finish(w);
    if (n == 0 && w->len) {
        fail(err, NMEA_ERR_TOO_LONG, "the text needs %n bytes and a NUL, the buffer holds %n");
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
            param_refuse(p, "parameter %n (%s): the value is above its maximum", err);
            return writer_finish(&w);
        }
    } else if (!param_in_range(p, (int64_t)value, 0, err)) {
        return writer_finish(&w);
    }
    if (p->size && p->size < 8 && value >> (8 * p->size)) {
        param_refuse(p, "parameter %n (%s): the value does not fit %n byte(s)", err);
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
    uint64_t unit = (uint64_t)POW10[scale];
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
    return param_refuse(p, "parameter %n (%s): more than 18 decimals", err);
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
        param_refuse(p, "parameter %n (%s): expected %n values, got %n", err);
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
        param_refuse(p, "parameter %n (%s): text longer than %n", err);
        err->num[1] = p->max_length;
        return writer_finish(&w);
    }
    for (i = 0; i < n; i++) {
        if (!is_printable(text[i]) || strchr(",*$!", text[i])) {
            param_refuse(p, "parameter %n (%s): text holds ',', '*', '$', '!' or a byte outside printable ASCII",
                         err);
            return writer_finish(&w);
        }
    }
    put_str(&w, text);
    return param_finish(&w, err);
}
#endif /* NMEA_NO_TABLES */

/* ------------------------------------------------------------------------------------------ */
/* Layouts: what the spec says of each sentence layout, as a table the generator writes (the
   LAYOUTS of nmea.c), and the one reader, writer, JSON writer and JSON collector that read
   them. Only the fast path has code of its own per layout. */

/* The field types of the spec. */
typedef enum {
    FIELD_KEYWORD,
    FIELD_INTEGER,
    FIELD_DECIMAL,
    FIELD_HEX,
    FIELD_TIME,
    FIELD_DATE,
    FIELD_LATITUDE,
    FIELD_LONGITUDE,
    FIELD_CHAR,
    FIELD_LITERAL,
    FIELD_TEXT,
    FIELD_ENUM,
    FIELD_ENUM_CHARS
} field_type;

/* A field of a layout, or of the entries of its repeated group. */
typedef struct {
    const char *id;
    const char *expected; /* what the field takes, for errors */
    const void *arg;      /* integer, decimal: its nmea_range (NULL: any value); enum, enum_chars:
                             its nmea_enum_def; keyword, literal: its word; latitude, longitude:
                             what the hemisphere takes */
    uint16_t offset;      /* of its member in the layout struct (or the entry); 0 for a keyword */
    uint8_t type;         /* field_type */
    uint8_t width;        /* wire fields: 2 for a latitude or longitude, else 1 */
    uint16_t max_length;  /* text, enum_chars: most characters (0: any number) */
} layout_field;

/* The fields of a layout without any (its `fields` point here, never NULL: no arithmetic on it;
   a spec in which every layout has fields leaves it unused). */
NMEA_INTERNAL const layout_field NO_FIELDS[1];

/* An offset of a member a layout does not have. */
#define NO_MEMBER 0xFFFFu

/* The repeated group of a layout: `min` to `max` entries of `width` wire fields. */
typedef struct {
    const char *id;
    const layout_field *fields; /* offsets in an entry (a single field: 0) */
    uint16_t field_count;
    uint16_t width;
    uint16_t min;
    uint16_t max;
    bool single;           /* one field an entry: the JSON lists its values without keys */
    uint16_t offset;       /* of its nmea_entries (NO_MEMBER: none, the entries hold only keywords) */
    uint16_t entry_size;   /* of an entry of nmea_entries.items */
    uint16_t count_offset; /* of the uint8_t entry count (NO_MEMBER: always `max` entries) */
} layout_group;

typedef enum { LAYOUT_STANDARD, LAYOUT_PROPRIETARY, LAYOUT_TEXT } layout_kind;

/* A sentence layout. Its fields are those before the group, after it, and the optional trailing
   ones, in wire order. */
typedef struct {
    const char *sentence;      /* the spec's sentence id */
    const char *address;       /* a proprietary sentence's address, a text command's word; NULL */
    const char *command;       /* a text command: its word in upper case; NULL */
    const char *variant;       /* NULL: the sentence's main layout */
    const char *selector;      /* the keyword (upper case) every line of it holds, or NULL */
    const layout_field *fields; /* NO_FIELDS: none */
    const layout_group *group;  /* NULL: none */
    uint16_t selector_at;      /* the selector's wire index (0-based) */
    uint16_t before;           /* fields before the group (all required ones without a group) */
    uint16_t after;            /* required fields after the group */
    uint16_t optional;         /* optional trailing fields */
    uint16_t fixed;            /* required wire fields besides the group */
    uint16_t max_fields;       /* wire fields at most (without a group) */
    uint16_t optional_max;     /* optional wire fields at most */
    uint16_t size;             /* of the struct */
    uint16_t head;             /* offset of the talker (standard) or as_received (text); NO_MEMBER */
    uint16_t optional_count;   /* offset of the uint8_t optional_count; NO_MEMBER */
    uint16_t checksum;         /* offset of the nmea_checksum_style; NO_MEMBER (a text command) */
    uint8_t kind;              /* layout_kind */
    char start;                /* '$' or '!' */
} layout;

static inline void *member_at(void *s, uint16_t offset)
{
    return (char *)s + offset;
}

static inline const void *const_member_at(const void *s, uint16_t offset)
{
    return (const char *)s + offset;
}

/* How many optional trailing fields `optional` wire fields hold (a latitude needs both of its). */
static size_t optional_present(const layout *l, size_t optional)
{
    const layout_field *f = l->fields + l->before + l->after;
    size_t n, wire = 0;
    for (n = 0; n < l->optional; n++) {
        wire += f[n].width;
        if (wire > optional)
            break;
    }
    return n;
}

/* The entries of a layout's group that are on the wire (a struct's count may be too big). */
static size_t entries_of(const layout_group *g, const void *s)
{
    size_t n;
    if (g->count_offset == NO_MEMBER)
        return g->max;
    n = *(const uint8_t *)const_member_at(s, g->count_offset);
    return n < g->max ? n : g->max;
}

/* The optional trailing fields of a struct that are on the wire. */
static size_t optional_of(const layout *l, const void *s)
{
    return l->optional_count == NO_MEMBER ? 0 : *(const uint8_t *)const_member_at(s, l->optional_count);
}

/* The entries of a layout's group (NULL: it stores nothing, its entries hold only keywords). */
static const nmea_entries *entries_in(const layout_group *g, const void *s)
{
    return g->offset == NO_MEMBER ? NULL : (const nmea_entries *)const_member_at(s, g->offset);
}

/* Reads field `f` into `out`, a value of its type (nothing for a keyword). */
static bool read_field(nmea_reader *r, const layout_field *f, void *out)
{
    switch ((field_type)f->type) {
    case FIELD_KEYWORD:
        return read_keyword(r, f->id, f->expected, f->arg);
    case FIELD_INTEGER:
        return read_integer(r, out, f->id, f->expected, f->arg);
    case FIELD_DECIMAL:
        return read_decimal(r, out, f->id, f->expected, f->arg);
    case FIELD_HEX:
        return read_hex(r, out, f->id, f->expected);
    case FIELD_TIME:
        return read_time(r, out, f->id, f->expected);
    case FIELD_DATE:
        return read_date(r, out, f->id, f->expected);
    case FIELD_LATITUDE:
        return read_latitude(r, out, f->id, f->expected, f->arg);
    case FIELD_LONGITUDE:
        return read_longitude(r, out, f->id, f->expected, f->arg);
    case FIELD_CHAR:
        return read_char(r, out, f->id, f->expected);
    case FIELD_LITERAL:
        return read_literal(r, out, f->id, f->expected, f->arg);
    case FIELD_TEXT:
        return read_text(r, out, f->id, f->expected, f->max_length);
    case FIELD_ENUM:
        return read_enum(r, out, f->id, f->expected, f->arg);
    case FIELD_ENUM_CHARS:
        return read_enum_chars(r, out, f->id, f->expected, f->arg, f->max_length);
    }
    return false;
}

static bool read_fields(nmea_reader *r, const layout_field *f, size_t n, void *entry)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (!read_field(r, &f[i], member_at(entry, f[i].offset)))
            return false;
    return true;
}

/* Any value a field holds, for reading one field of a group entry on its own. */
typedef union {
    nmea_number number;
    nmea_hex hex;
    nmea_time time;
    nmea_date date;
    nmea_coordinate coordinate;
    char c;
    bool literal;
    nmea_text text;
    nmea_enum enumeration;
} field_value;

/* The size of the value of field `f` (0: a keyword holds none). */
static size_t field_size(const layout_field *f)
{
    switch ((field_type)f->type) {
    case FIELD_KEYWORD:
        return 0;
    case FIELD_INTEGER:
    case FIELD_DECIMAL:
        return sizeof(nmea_number);
    case FIELD_HEX:
        return sizeof(nmea_hex);
    case FIELD_TIME:
        return sizeof(nmea_time);
    case FIELD_DATE:
        return sizeof(nmea_date);
    case FIELD_LATITUDE:
    case FIELD_LONGITUDE:
        return sizeof(nmea_coordinate);
    case FIELD_CHAR:
        return sizeof(char);
    case FIELD_LITERAL:
        return sizeof(bool);
    case FIELD_TEXT:
    case FIELD_ENUM_CHARS:
        return sizeof(nmea_text);
    case FIELD_ENUM:
        return sizeof(nmea_enum);
    }
    return 0;
}

/* The end of the `n` fields (n > 0) that start at `p`, before `end`. */
static const char *fields_end(const char *p, const char *end, char sep, size_t n)
{
    for (;; p++) {
        while (p < end && *p != sep)
            p++;
        if (p == end || --n == 0)
            return p;
    }
}

/* Reads a parsed sentence's group entries again, field by field, from their wire text. */
typedef struct {
    nmea_reader r;
    nmea_error err;
} entry_reader;

static bool entry_reader_at(entry_reader *c, const layout *l, const nmea_entries *e, size_t i);

/* The next field `f` of an entry, into `out`, as parsing read it (lenient parsing's blanks
   included). A field that does not read (in a struct the parser did not make) is empty. */
static void reread_field(entry_reader *c, const layout_field *f, void *out)
{
    const char *next = c->r.next;
    unsigned index = c->r.index;
    size_t size = field_size(f);

    if (size)
        memset(out, 0, size);
    if (read_field(&c->r, f, out))
        return;
    if (size)
        memset(out, 0, size);
    c->r.next = fields_end(next, c->r.end, c->r.sep, f->width);
    c->r.next += c->r.next < c->r.end;
    c->r.index = index + f->width;
}

/* Reads the wire into `s`, a struct of layout `l`. */
NMEA_OUTLINE bool read_with(const layout *l, void *s, const nmea_wire *wire, nmea_error *err)
{
    const layout_group *g = l->group;
    nmea_reader r;
    size_t i, repeats = 0, optional, present;

    reader_start(&r, wire, l->sentence, err);
    if (g ? !read_group_count(&r, wire->count, g->id, l->fixed, g->width, g->min, g->max, l->optional_max, &repeats,
                              &optional)
          : !read_count(&r, wire->count, l->fixed, l->max_fields, &optional))
        return false;
    clear_layout(s, l->size);
    if (l->head != NO_MEMBER)
        *(nmea_text *)member_at(s, l->head) = l->kind == LAYOUT_TEXT ? wire->line : wire->address;
    if (l->checksum != NO_MEMBER)
        *(nmea_checksum_style *)member_at(s, l->checksum) = wire->checksum;
    present = optional_present(l, optional);
    if (l->optional_count != NO_MEMBER)
        *(uint8_t *)member_at(s, l->optional_count) = (uint8_t)present;
    if (!read_fields(&r, l->fields, l->before, s))
        return false;
    if (g) {
        const char *start = r.next;
        unsigned first = r.index;
        field_value value;
        size_t j;
        for (i = 0; i < repeats; i++) {
            reader_entry(&r, g->id, i);
            for (j = 0; j < g->field_count; j++)
                if (!read_field(&r, &g->fields[j], &value))
                    return false;
        }
        if (g->offset != NO_MEMBER) { /* the entries stay on the wire, read when asked for */
            nmea_entries *e = (nmea_entries *)member_at(s, g->offset);
            e->wire = text_span(start, repeats ? fields_end(start, r.end, r.sep, repeats * g->width) : start);
            for (j = 0; j < wire->blanks; j++)
                if (wire->blank[j] > first && wire->blank[j] <= r.index)
                    e->blank[e->blanks++] = (uint16_t)(wire->blank[j] - first);
        }
        if (g->count_offset != NO_MEMBER)
            *(uint8_t *)member_at(s, g->count_offset) = (uint8_t)repeats;
        reader_entry(&r, NULL, 0);
    }
    return read_fields(&r, l->fields + l->before, l->after + present, s);
}

/* Starts `c` at entry `i` of the group of layout `l` whose entries `e` holds on the wire; false
   when the wire ends before it. */
static bool entry_reader_at(entry_reader *c, const layout *l, const nmea_entries *e, size_t i)
{
    nmea_wire w;
    const char *p = e->wire.ptr, *end = p ? p + e->wire.len : NULL;
    size_t skip;

    memset(&w, 0, sizeof w);
    w.sep = l->kind == LAYOUT_TEXT ? ' ' : ',';
    w.ignore_case = l->kind == LAYOUT_TEXT;
    for (skip = i * l->group->width; skip > 0; skip--) {
        p = fields_end(p, end, w.sep, 1);
        if (p == end)
            return false;
        p++;
    }
    if (p == NULL || (p == end && i > 0))
        return false;
    w.fields = text_span(p, end);
    reader_start(&c->r, &w, l->sentence, &c->err);
    c->r.index = (unsigned)(i * l->group->width); /* the blanks count from the first entry */
    c->r.blank = e->blank;
    c->r.blanks = e->blanks < NMEA_MAX_PROBLEMS ? e->blanks : NMEA_MAX_PROBLEMS;
    return true;
}

/* Entry `i` of the group of `s`, a struct of layout `l`, into `out` (an entry, or the value of a
   group of one field): false when the group has fewer entries. */
NMEA_OUTLINE bool entry_of(const layout *l, const void *s, size_t i, void *out)
{
    const layout_group *g = l->group;
    const nmea_entries *e = entries_in(g, s);
    entry_reader c;
    size_t j;

    if (i >= entries_of(g, s))
        return false;
    if (e->items) {
        memcpy(out, (const char *)e->items + i * g->entry_size, g->entry_size);
        return true;
    }
    memset(out, 0, g->entry_size);
    if (!entry_reader_at(&c, l, e, i))
        return true; /* past what the wire holds: an empty entry */
    for (j = 0; j < g->field_count; j++)
        reread_field(&c, &g->fields[j], member_at(out, g->fields[j].offset));
    return true;
}

/* Writes field `f` (its separator and text) from `in`, a value of its type. */
static void write_field(nmea_writer *w, const layout_field *f, const void *in)
{
    switch ((field_type)f->type) {
    case FIELD_KEYWORD:
        put_keyword(w, f->arg);
        break;
    case FIELD_INTEGER:
    case FIELD_DECIMAL:
        put_number(w, in);
        break;
    case FIELD_HEX:
        put_hex(w, in);
        break;
    case FIELD_TIME:
        put_time(w, in);
        break;
    case FIELD_DATE:
        put_date(w, in);
        break;
    case FIELD_LATITUDE:
    case FIELD_LONGITUDE:
        put_coordinate(w, in);
        break;
    case FIELD_CHAR:
        put_char_field(w, *(const char *)in);
        break;
    case FIELD_LITERAL:
        put_literal(w, *(const bool *)in, f->arg);
        break;
    case FIELD_TEXT:
    case FIELD_ENUM_CHARS:
        put_text_field(w, *(const nmea_text *)in);
        break;
    case FIELD_ENUM:
        put_enum(w, in, f->arg);
        break;
    }
}

static void write_fields(nmea_writer *w, const layout_field *f, size_t n, const void *entry)
{
    size_t i;
    for (i = 0; i < n; i++)
        write_field(w, &f[i], const_member_at(entry, f[i].offset));
}

/* The entries of a group: from the caller's array, else their fields as received (a field a
   problem names is written with the problem's text, which is the same). The fields of entries
   neither holds are empty; a group of keywords writes its keywords. */
static void write_entries(nmea_writer *w, const layout_group *g, const void *s)
{
    const nmea_entries *e = entries_in(g, s);
    size_t i, n = entries_of(g, s);
    const char *p, *end, *stop;

    if (e && e->items) {
        for (i = 0; i < n; i++)
            write_fields(w, g->fields, g->field_count, (const char *)e->items + i * g->entry_size);
        return;
    }
    if (!e) {
        for (i = 0; i < n; i++)
            write_fields(w, g->fields, g->field_count, s);
        return;
    }
    p = e->wire.ptr;
    end = p ? p + e->wire.len : NULL;
    for (i = 0; i < n * g->width; i++) {
        stop = fields_end(p, end, w->sep, 1);
        /* (a field lenient parsing read as empty is written empty, or as its problem's text) */
        if (!put_sep(w) && stop != p && !(e->blanks && is_blank(e->blank, e->blanks, (unsigned)i + 1)))
            put_text(w, text_span(p, stop));
        p = stop < end ? stop + 1 : stop;
    }
}

/* Writes `s`, a struct of layout `l`, with the texts of its `problems` (NULL: none) in their
   places. */
NMEA_OUTLINE void write_with(nmea_writer *w, const layout *l, const void *s, const nmea_problems *problems)
{
    const layout_group *g = l->group;

    if (l->kind == LAYOUT_STANDARD)
        begin_sentence(w, l->start, *(const nmea_text *)const_member_at(s, l->head), l->sentence, problems);
    else if (l->kind == LAYOUT_PROPRIETARY)
        begin_sentence(w, '$', nmea_text_of(NULL), l->address, problems);
    else
        begin_text(w, l->address, *(const nmea_text *)const_member_at(s, l->head), problems);
    write_fields(w, l->fields, l->before, s);
    if (g)
        write_entries(w, g, s);
    write_fields(w, l->fields + l->before, l->after + optional_of(l, s), s);
    if (l->kind == LAYOUT_TEXT)
        end_text(w);
    else
        end_sentence(w, *(const nmea_checksum_style *)const_member_at(s, l->checksum));
}

/* The sentence `s` of layout `l` (with `problems`, NULL: none) written to buf. */
static size_t serialize_with(const layout *l, const void *s, const nmea_problems *problems, char *buf, size_t cap)
{
    nmea_writer w = writer_of(buf, cap);
    write_with(&w, l, s, problems);
    return writer_finish(&w);
}

/* nmea_build_*: the sentence written, then read back into `check` (a struct of the layout). */
static size_t build_with(const layout *l, const void *s, const nmea_problems *problems, void *check, char *buf,
                         size_t cap, nmea_error *err)
{
    nmea_writer w = writer_of(buf, cap);
    nmea_wire wire;

    write_with(&w, l, s, problems);
    if (!build_wire(&w, l->kind == LAYOUT_TEXT, &wire, err) || !read_with(l, check, &wire, err))
        return build_failed(&w);
    return build_end(&w);
}

#ifndef NMEA_NO_JSON
/* A field in the JSON under `key` (NULL: a value of a group's array), from `in`, a value of its
   type. */
static void json_field(nmea_writer *w, const char *key, const layout_field *f, const void *in, bool values)
{
    switch ((field_type)f->type) {
    case FIELD_KEYWORD:
        json_keyword(w, key, f->arg, values);
        break;
    case FIELD_INTEGER:
    case FIELD_DECIMAL:
        json_number(w, key, in, values);
        break;
    case FIELD_HEX:
        json_hex(w, key, in, values);
        break;
    case FIELD_TIME:
        json_time(w, key, in, values);
        break;
    case FIELD_DATE:
        json_date(w, key, in, values);
        break;
    case FIELD_LATITUDE:
    case FIELD_LONGITUDE:
        json_coordinate(w, key, in, values);
        break;
    case FIELD_CHAR:
        json_char(w, key, *(const char *)in, values);
        break;
    case FIELD_LITERAL:
        json_literal(w, key, *(const bool *)in, f->arg, values);
        break;
    case FIELD_TEXT:
        json_text(w, key, *(const nmea_text *)in, values);
        break;
    case FIELD_ENUM:
        json_enum(w, key, in, f->arg, values);
        break;
    case FIELD_ENUM_CHARS:
        json_enum_chars(w, key, *(const nmea_text *)in, f->arg, values);
        break;
    }
}

static void json_fields(nmea_writer *w, const layout_field *f, size_t n, const void *entry, bool values)
{
    size_t i;
    for (i = 0; i < n; i++)
        json_field(w, f[i].id, &f[i], const_member_at(entry, f[i].offset), values);
}

/* The lossless fields of a text command written back as received: each word as written, under
   the ids of the layout's fields in order. */
static void json_words_as_received(nmea_writer *w, const layout *l, nmea_text line)
{
    const char *p = line.ptr, *end = line.ptr + line.len, *space;
    size_t i, count = l->before + l->optional;
    p = memchr(p, ' ', line.len);
    for (i = 0; p && i < count; i++) {
        p++;
        space = memchr(p, ' ', (size_t)(end - p));
        json_key(w, l->fields[i].id);
        if (p == (space ? space : end))
            put_str(w, "null");
        else
            put_json_str(w, text_span(p, space ? space : end), 0);
        p = space;
    }
}

/* The lossless fields of a text command written in the spec's letter case, as the reference
   shows them: each word under its field id, the text of a problem in place of the field's. */
static void json_words_as_written(nmea_writer *w, const layout *l, const void *s, const nmea_problems *problems)
{
    size_t i, count = l->before + optional_of(l, s);
    for (i = 0; i < count; i++)
        if (!problems || !json_problem_word(w, l->fields[i].id, problems, (unsigned)i + 1))
            json_field(w, l->fields[i].id, &l->fields[i], const_member_at(s, l->fields[i].offset), false);
}

/* The entries of the group of `s`, a struct of layout `l`: from the caller's array, else read
   again from the wire field by field. */
static void json_entries(nmea_writer *w, const layout *l, const void *s, bool values)
{
    const layout_group *g = l->group;
    const nmea_entries *e = entries_in(g, s);
    size_t i, j, n = entries_of(g, s);
    bool on_wire = false;
    entry_reader c;
    field_value value;
    const void *in;

    memset(&c, 0, sizeof c);
    json_open(w, g->id, '[');
    for (i = 0; i < n; i++) {
        if (!e || !e->items)
            on_wire = i == 0 ? e && entry_reader_at(&c, l, e, 0) : on_wire && c.r.next < c.r.end;
        if (!g->single)
            json_open(w, NULL, '{');
        for (j = 0; j < g->field_count; j++) {
            const layout_field *f = &g->fields[j];
            if (e && e->items) {
                in = (const char *)e->items + i * g->entry_size + f->offset;
            } else {
                memset(&value, 0, sizeof value);
                if (on_wire)
                    reread_field(&c, f, &value);
                in = &value;
            }
            json_field(w, g->single ? NULL : f->id, f, in, values);
        }
        if (!g->single)
            json_close(w, '}');
    }
    json_close(w, ']');
}

/* The decode JSON of `s`, a struct of layout `l`, with its `problems` (NULL: none). */
NMEA_OUTLINE void json_with(nmea_writer *w, const layout *l, const void *s, const nmea_problems *problems,
                            bool values)
{
    const layout_group *g = l->group;
    nmea_writer sentence = writer_of(NULL, 0);
    nmea_checksum_style checksum = NMEA_CHECKSUM_NONE;

    write_with(&sentence, l, s, problems);
    if (l->checksum != NO_MEMBER)
        checksum = *(const nmea_checksum_style *)const_member_at(s, l->checksum);
    if (l->kind == LAYOUT_STANDARD) {
        json_begin_sentence(w, l->start, *(const nmea_text *)const_member_at(s, l->head), l->sentence, l->variant);
    } else if (l->kind == LAYOUT_PROPRIETARY) {
        json_begin_proprietary(w, "$", nmea_text_of(l->address), l->sentence, l->variant);
    } else {
        nmea_text as_received = *(const nmea_text *)const_member_at(s, l->head);
        json_begin_proprietary(w, "", text_address(&sentence, as_received, l->address), l->sentence, l->variant);
        if (!values) {
            if (sentence.matched)
                json_words_as_received(w, l, as_received);
            else
                json_words_as_written(w, l, s, problems);
            json_end_sentence(w, &sentence, checksum, problems);
            return;
        }
    }
    json_fields(w, l->fields, l->before, s, values);
    if (g)
        json_entries(w, l, s, values);
    json_fields(w, l->fields + l->before, l->after + optional_of(l, s), s, values);
    json_end_sentence(w, &sentence, checksum, problems);
}

/* The wire fields of a `fields` object of decode's JSON for layout `l`, in wire order. */
static bool collect_with(const layout *l, nmea_collector *c, nmea_json fields)
{
    const layout_field *f = l->fields;
    const layout_group *g = l->group;
    nmea_json entries, entry;
    size_t i;

    for (i = 0; i < l->before; i++)
        if (!collect_field(c, fields, f[i].id, f[i].width))
            return false;
    if (g) {
        if (!collect_group(c, fields, g->id, &entries))
            return false;
        while (json_next(&entries, &entry))
            for (i = 0; i < g->field_count; i++)
                if (!(g->single ? collect_value(c, entry, g->fields[i].width)
                                : collect_field(c, entry, g->fields[i].id, g->fields[i].width)))
                    return false;
    }
    for (f += l->before, i = 0; i < l->after; i++)
        if (!collect_field(c, fields, f[i].id, f[i].width))
            return false;
    for (f += l->after, i = 0; i < l->optional; i++)
        if (!collect_optional(c, fields, f[i].id, f[i].width))
            return false;
    return true;
}
#endif /* NMEA_NO_JSON */
