/* Framing: a line split into start, address and fields, its checksum verified (eight bytes at a
   time), a text command's words; and the other direction, the frame of a sentence being written
   (begin_sentence, end_sentence with its checksum, a text command's words, a generic sentence). */

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
NMEA_INLINE uint64_t zero_bytes(uint64_t word)
{
    return ~(((word & BYTES_LOW7) + BYTES_LOW7) | word | BYTES_LOW7);
}

/* The bytes that end the body of a sentence: '*', and whatever is not printable ASCII (below
   0x20, 0x7F and above). */
NMEA_INLINE uint64_t body_end_bytes(uint64_t word)
{
    uint64_t low7 = word & BYTES_LOW7;
    return ((word | ~(low7 + 0x60 * BYTES_ONES) | (low7 + BYTES_ONES)) & BYTES_HIGH)
           | zero_bytes(word ^ ('*' * BYTES_ONES));
}

/* How many bytes a byte mask marks. */
NMEA_INLINE size_t count_bytes(uint64_t mask)
{
    return (size_t)(((mask >> 7) * BYTES_ONES) >> 56);
}

static bool ends_body(unsigned char c)
{
    return c < 0x20 || c > 0x7E || c == '*';
}

/* What frame_line checks beyond the form of a line (`checks`): FRAME_REQUIRE_CHECKSUM refuses a
   sentence without a checksum (or with a bare '*'); FRAME_STRICT refuses a one-digit checksum,
   which is otherwise kept (NMEA_CHECKSUM_SHORT_*) when it equals the sum. */
#define FRAME_REQUIRE_CHECKSUM 1u
#define FRAME_STRICT 2u

/* One pass over the line: the printable check, the checksum and the field count, with the
   `checks` above. */
static bool frame_line(nmea_frame *f, const char *line, size_t len, unsigned checks, nmea_error *err)
{
    size_t i, star = 0, comma = 0, commas = 0, body_end;
    unsigned sum = 0;
    int high = -1, low = -1; /* the checksum's hex digits */
#ifndef NMEA_NO_FAST_PATH
    size_t words_end;
    uint64_t word, words = 0;
#endif
    bool named = false, lower = false, upper = false;
    nmea_text sent;

#ifdef NMEA_NO_PROBLEMS /* every sentence is read strictly */
    checks |= FRAME_STRICT;
#endif
    if (len > NMEA_MAX_LINE) {
        nmea_error_too_long(err, len);
        return false;
    }
    if (len == 0)
        return fail(err, NMEA_ERR_NOT_A_SENTENCE, ERROR_TEXT("empty line"));
    if (line[0] != '$' && line[0] != '!')
        return fail(err, NMEA_ERR_NOT_A_SENTENCE, ERROR_TEXT("line does not start with '$' or '!'"));
#ifndef NMEA_NO_FAST_PATH /* for speed only: the byte loops below read any line alike */
    if (len > 6 && line[6] == ',' && is_alnum(line[1]) && is_alnum(line[2]) && is_alnum(line[3])
        && is_alnum(line[4]) && is_alnum(line[5])) { /* the usual address: talker and sentence id */
        named = true;
        sum = (unsigned char)(line[1] ^ line[2] ^ line[3] ^ line[4] ^ line[5] ^ ',');
        commas = 1;
        comma = 6;
        i = 7;
    } else
#endif
    {
        for (i = 1; i < len && !ends_body((unsigned char)line[i]); i++) { /* the address */
            sum ^= (unsigned char)line[i];
            if (line[i] == ',') {
                commas = 1;
                comma = i++;
                break;
            }
        }
    }
#ifndef NMEA_NO_FAST_PATH
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
    words ^= words >> 32;
    words ^= words >> 16;
    words ^= words >> 8;
    sum ^= (unsigned char)words;
#endif
    for (; i < len && !ends_body((unsigned char)line[i]); i++) { /* the rest of the body */
        sum ^= (unsigned char)line[i];
        commas += line[i] == ',';
    }
    if (i < len && line[i] == '*')
        for (star = i++; i < len && is_printable(line[i]); i++)
            continue;
    if (i < len) {
        fail(err, NMEA_ERR_NOT_A_SENTENCE, ERROR_TEXT("byte 0x%x at offset %n is not printable ASCII"));
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
        } else if (sent.len == 1 && !(checks & FRAME_STRICT) && hex_value(sent.ptr[0]) == (int)sum) {
            /* one digit that is the checksum (OpenCPN's instrument captures): kept as sent */
            high = 0;
            low = (int)sum;
            lower = sent.ptr[0] >= 'a' && sent.ptr[0] <= 'f';
        }
        if (high < 0 || low < 0 || (lower && upper)) {
            fail(err, NMEA_ERR_BAD_CHECKSUM, ERROR_TEXT("checksum %q is not two hex digits of one letter case"));
            err->text = sent;
            if (named)
                set_address(err, f->address, NULL);
            return false;
        }
        if ((unsigned)(high * 16 + low) != sum) {
            fail(err, NMEA_ERR_CHECKSUM_MISMATCH, ERROR_TEXT("checksum is %t, computed %X"));
            err->text = sent;
            err->num[0] = sum;
            if (named)
                set_address(err, f->address, NULL);
            return false;
        }
        f->checksum = sent.len == 1 ? (lower ? NMEA_CHECKSUM_SHORT_LOWER : NMEA_CHECKSUM_SHORT_UPPER)
                                    : (lower ? NMEA_CHECKSUM_LOWER : NMEA_CHECKSUM_UPPER);
    }
    if (!named) {
        fail(err, NMEA_ERR_NOT_A_SENTENCE, ERROR_TEXT("address %q is not letters and digits"));
        err->text = f->address;
        return false;
    }
    if ((checks & FRAME_REQUIRE_CHECKSUM) && (f->checksum == NMEA_CHECKSUM_NONE || f->checksum == NMEA_CHECKSUM_EMPTY)) {
        fail(err, NMEA_ERR_MISSING_CHECKSUM, ERROR_TEXT("the sentence has no checksum"));
        set_address(err, f->address, NULL);
        return false;
    }
    f->count = commas;
    f->fields = commas ? text_span(line + comma + 1, line + body_end) : text_span(line + body_end, line + body_end);
    return true;
}

/* The standard query's formatter ($CCGPQ,GGA: CC asks GP for GGA): its talker is two talker IDs. */
#define QUERY_FORMATTER "Q"

/* How many characters the talker of standard sentence `sentence` has: 2, or 4 for the query. */
static size_t talker_length(const char *sentence)
{
    return strcmp(sentence, QUERY_FORMATTER) == 0 ? 4 : 2;
}

/* A talker ID and a sentence formatter: '$' (or '!', an encapsulation sentence such as AIS VDM),
   5 characters (6 for a receiver's 4-character formatter, Unicore's GGAH), not proprietary
   ('P...'). */
static bool is_standard_address(const nmea_frame *f)
{
    return f->start.len == 1 && (f->start.ptr[0] == '$' || f->start.ptr[0] == '!') &&
           (f->address.len == 5 || f->address.len == 6) && f->address.ptr[0] != 'P';
}

/* A text command (ComNav: words separated by single spaces, no '$', no checksum): the first
   word is the address, the others are the fields. */
/* Whether every byte of the line is printable ASCII; the first that is not is the error. */
static bool all_printable(const char *line, size_t len, nmea_error *err)
{
    size_t i;
    for (i = 0; i < len; i++) {
        if (!is_printable(line[i])) {
            fail(err, NMEA_ERR_NOT_A_SENTENCE, ERROR_TEXT("byte 0x%x at offset %n is not printable ASCII"));
            err->num[0] = (unsigned char)line[i];
            err->num[1] = i;
            return false;
        }
    }
    return true;
}

static bool text_frame(nmea_frame *f, const char *line, size_t len, nmea_error *err)
{
    size_t i, space = 0, spaces = 0;

    if (len > NMEA_MAX_LINE) {
        nmea_error_too_long(err, len);
        return false;
    }
    if (!all_printable(line, len, err))
        return false;
    for (i = 0; i < len; i++) {
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

/* Whether a checksum `sum` in `style` is written as one digit: a one-digit style while the sum
   fits one (the tools' JSON then lists a short_checksum problem). */
static bool checksum_is_short(nmea_checksum_style style, unsigned sum)
{
    return (style == NMEA_CHECKSUM_SHORT_UPPER || style == NMEA_CHECKSUM_SHORT_LOWER) && sum < 16;
}

/* The checksum's hex digits in `style` (upper or lower case, one digit when checksum_is_short)
   put in `out`; returns how many. */
static size_t checksum_digits(char *out, nmea_checksum_style style, unsigned char sum)
{
    const char *hex = style == NMEA_CHECKSUM_LOWER || style == NMEA_CHECKSUM_SHORT_LOWER ? HEX_LOWER : HEX_UPPER;
    if (checksum_is_short(style, sum)) {
        out[0] = hex[sum];
        return 1;
    }
    out[0] = hex[sum >> 4];
    out[1] = hex[sum & 15];
    return 2;
}

static void end_sentence(nmea_writer *w, nmea_checksum_style style)
{
    char digits[2];
    size_t i, n;
    stop_sum(w);
    w->problems = NULL;
    if (style == NMEA_CHECKSUM_NONE)
        return;
    put_char(w, '*');
    if (style == NMEA_CHECKSUM_EMPTY)
        return;
    for (i = 0, n = checksum_digits(digits, style, w->sum); i < n; i++)
        put_char(w, digits[i]);
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
