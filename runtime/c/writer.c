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

NMEA_INLINE void put_char(nmea_writer *w, char c)
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

NMEA_INLINE void put_mem(nmea_writer *w, const char *s, size_t n)
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

NMEA_INLINE char *uint_text(char *end, uint64_t v, unsigned width)
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

/* `n` characters escaped once for a JSON string into `out` (room for 6 each): '"' and '\\' behind a
   backslash, anything not printable (or every character, `wide`: the low bytes of characters above
   0xFF) as \u00hh. The length written. */
static size_t escape_once(const char *in, size_t n, bool wide, char *out)
{
    size_t i, len = 0;
    for (i = 0; i < n; i++) {
        char c = in[i];
        unsigned char u = (unsigned char)c;
        if (!wide && (c == '"' || c == '\\')) {
            out[len++] = '\\';
            out[len++] = c;
        } else if (wide || !is_printable(c)) {
            memcpy(out + len, "\\u00", 4);
            out[len + 4] = HEX_LOWER[u >> 4];
            out[len + 5] = HEX_LOWER[u & 15];
            len += 6;
        } else {
            out[len++] = c;
        }
    }
    return len;
}

/* A character of a JSON string escaped `depth` times (at most twice: a quoted text inside an
   error message inside JSON), a level at a time, without recursion; `wide`: `c` is the low byte
   of a character above 0xFF, which the tools escape as \u00hh of that byte. */
static void put_escaped_char(nmea_writer *w, char c, bool wide, int depth)
{
    char once[6], twice[36];
    size_t n;
    if (depth == 0) {
        put_char(w, c);
        return;
    }
    n = escape_once(&c, 1, wide, once);
    if (depth == 1) {
        put_mem(w, once, n);
        return;
    }
    put_mem(w, twice, escape_once(once, n, false, twice));
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
