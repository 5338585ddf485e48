/* The stream framer (nmea_framer): bytes as a serial port or socket delivers them, in chunks of
   any size, cut into lines at CR, LF, '$' and '!', an overlong line reported by its length. A
   '\' at the start of a line opens a TAG block, which keeps its sentence: up to the block's
   closing '\' every byte but CR and LF belongs to it, and a '$', '!' or '\' right after that
   continues the line (unless -DNMEA_NO_TAG_BLOCKS: a '\' is then a byte like any other). Unless
   -DNMEA_NO_BINARY_FRAMES, the first sync byte of a binary protocol of spec/binary (the generated
   table nmea_framings) outside a TAG block starts a frame, which the next byte names (bytes that
   start no frame of any protocol are the line's) and its checksum decides (runtime.h). */

/* The bytes that end a line (CR, LF), start a new one ('$', '!'), open or close a TAG block, or
   may start a binary frame (the first sync byte of a protocol: 4; '$' when it starts SBF's too). */
static const unsigned char LINE_BOUNDARY[256] = {['\r'] = 1, ['\n'] = 1, ['!'] = 2, ['\\'] = 3,
#ifndef NMEA_NO_BINARY_FRAMES
                                                 ['$'] = NMEA_FRAME_DOLLAR, NMEA_FRAME_SYNCS
#else
                                                 ['$'] = 2
#endif
};

/* Where the line being framed is as to TAG blocks (nmea_framer.tag). */
enum { FRAMER_OUTSIDE, FRAMER_IN_TAG, FRAMER_AFTER_TAG };

/* What framer_scan stops at besides a line's end (1) and the next line's start (2). */
enum { FRAMER_SYNC = 3 };

#ifndef NMEA_NO_BINARY_FRAMES
static unsigned frame_protocol(unsigned char first, unsigned char next);
#endif

void nmea_framer_init(nmea_framer *f)
{
    f->length = 0;
    f->next = 0;
    f->tag = FRAMER_OUTSIDE;
#ifndef NMEA_NO_BINARY_FRAMES
    f->frame_len = 0;
    f->replay = 0;
#endif
}

/* A line of `len` bytes at `ptr` (NULL when it is too long) as the item in *out. */
static bool framed_line(nmea_framed *out, const char *ptr, size_t len)
{
    out->ptr = len <= NMEA_MAX_LINE ? ptr : NULL;
    out->len = len;
#ifndef NMEA_NO_BINARY_FRAMES
    out->protocol = NMEA_LINE;
    out->error = NMEA_FRAME_OK;
#endif
    return true;
}

/* What `byte`, after `length` bytes of the line, is to it: 0 a byte of the line, 1 its end, 2 the
   start of the next line; moves f->tag on. (No table: a firmware that feeds links none.) */
static unsigned framer_step(nmea_framer *f, size_t length, char byte)
{
    unsigned kind = byte == '\r' || byte == '\n' ? 1 : byte == '$' || byte == '!' ? 2 : 0;
#ifndef NMEA_NO_TAG_BLOCKS
    if (f->tag != FRAMER_OUTSIDE) {
        if (kind == 1)
            return 1;
        if (byte == '\\')
            f->tag = f->tag == FRAMER_IN_TAG ? FRAMER_AFTER_TAG : FRAMER_IN_TAG;
        else if (f->tag == FRAMER_AFTER_TAG)
            f->tag = FRAMER_OUTSIDE; /* the sentence after the blocks, or whatever else follows */
        return 0;
    }
    if (byte == '\\' && length == 0)
        f->tag = FRAMER_IN_TAG;
#else
    (void)f;
#endif
    return kind == 2 && length == 0 ? 0 : kind;
}

/* The first byte from `p` on (the line holding `length` bytes before it) that ends the line,
   starts the next or may start a binary frame, with *boundary what it is; `end` when none does. */
static const char *framer_scan(nmea_framer *f, const char *p, const char *end, size_t length, unsigned *boundary)
{
    const char *q;
    for (q = p; q < end; q++) {
        if (f->tag == FRAMER_OUTSIDE) {
            if (!LINE_BOUNDARY[(unsigned char)*q])
                continue; /* the common byte, decided without a call */
#ifndef NMEA_NO_BINARY_FRAMES
            /* a first sync byte, unless the next byte, in the chunk, starts no frame with it: then
               it is the line's ('$' starts the next one) */
            if (LINE_BOUNDARY[(unsigned char)*q] == 4 &&
                (q + 1 == end || frame_protocol((unsigned char)*q, (unsigned char)q[1]) != 0)) {
                *boundary = FRAMER_SYNC;
                return q;
            }
#endif
        }
        if ((*boundary = framer_step(f, length + (size_t)(q - p), *q)) != 0)
            return q;
    }
    return end;
}

/* Starts the line with the '$' or '!' that ended the one nmea_framer_feed handed on last. */
static void framer_resume(nmea_framer *f)
{
    if (f->next) {
        f->line[0] = f->next;
        f->length = 1;
        f->next = 0;
    }
}

/* Adds bytes to the line being assembled (only its first NMEA_MAX_LINE bytes are kept). */
static void framer_keep(nmea_framer *f, const char *p, size_t n)
{
    if (f->length < NMEA_MAX_LINE)
        memcpy(f->line + f->length, p, n < NMEA_MAX_LINE - f->length ? n : NMEA_MAX_LINE - f->length);
    f->length += n;
}

/* Hands on the line under way, if it has bytes. */
static bool framer_end_line(nmea_framer *f, nmea_framed *out)
{
    size_t length;
    framer_resume(f);
    f->tag = FRAMER_OUTSIDE;
    if (f->length == 0)
        return false;
    length = f->length;
    f->length = 0;
    return framed_line(out, f->line, length);
}

/* One byte of a line: true when it completes one (nmea_framer_feed without binary frames). */
static bool framer_line_byte(nmea_framer *f, char byte, nmea_framed *out)
{
    unsigned boundary;
    framer_resume(f);
    boundary = framer_step(f, f->length, byte);
    if (!boundary) {
        if (f->length < NMEA_MAX_LINE) /* not framer_keep: a firmware that feeds links no memcpy */
            f->line[f->length] = byte;
        f->length++;
        return false;
    }
    if (f->length == 0) /* an empty line */
        return false;
    framed_line(out, f->line, f->length);
    f->length = 0;
    f->tag = FRAMER_OUTSIDE;
    f->next = boundary == 2 ? byte : 0; /* the line handed on is still in f->line */
    return true;
}

#ifndef NMEA_NO_BINARY_FRAMES
/* The framing of the frame under way (spec/binary/<protocol>/protocol.yaml). */
#define FRAMING(f) (&nmea_framings[(f)->protocol - 1])

/* The protocol whose frames start with `first` then `next` (0: none). */
static unsigned frame_protocol(unsigned char first, unsigned char next)
{
    unsigned i;
    for (i = 0; i < NMEA_FRAMING_COUNT; i++)
        if (nmea_framings[i].sync[0] == first && (next & nmea_framings[i].follow_mask) == nmea_framings[i].sync[1])
            return i + 1;
    return 0;
}

/* The bytes after the payload: the checksum (unless it sits in the header) and end bytes. */
static size_t frame_trailer_len(const nmea_framing *p)
{
    return (size_t)(p->check_at ? 0 : p->check_size) + p->end_len;
}

/* The frame's bytes, sync to end, from its header. */
static size_t frame_size(const nmea_framing *p, const unsigned char *h)
{
    size_t length = h[p->length_at];
    if (p->length_size == 2)
        length = p->big_endian ? length << 8 | h[p->length_at + 1] : length | (size_t)h[p->length_at + 1] << 8;
    return (length & p->length_mask) + p->length_adds;
}

/* The checksum of a frame's `len` bytes before its checksum, as it is sent read as a big-endian
   number (each kind of nmea_checksum_kind that a protocol of the build uses). */
static unsigned long frame_checksum(const nmea_framing *p, const unsigned char *frame, size_t len)
{
    unsigned long sum = 0;
    size_t i = p->check_from;
#if defined(NMEA_FRAMING_CRC24Q) || defined(NMEA_FRAMING_CRC16_CCITT)
    unsigned bit;
#endif
    switch (p->checksum) {
#ifdef NMEA_FRAMING_FLETCHER8
    case NMEA_CHECKSUM_FLETCHER8: {
        unsigned a = 0, b = 0;
        for (; i < len; i++) {
            a = (a + frame[i]) & 0xFF;
            b = (b + a) & 0xFF;
        }
        return (unsigned long)a << 8 | b;
    }
#endif
#ifdef NMEA_FRAMING_XOR8
    case NMEA_CHECKSUM_XOR8:
        for (; i < len; i++)
            sum ^= frame[i];
        return sum;
#endif
#ifdef NMEA_FRAMING_SUM15
    case NMEA_CHECKSUM_SUM15:
        for (; i < len; i++)
            sum += frame[i];
        return sum & 0x7FFF;
#endif
#ifdef NMEA_FRAMING_SUM32
    case NMEA_CHECKSUM_SUM32: /* little-endian words: the byte at 4k + j weighs 2^(8j) */
        for (; i < len; i++)
            sum = (sum + ((unsigned long)frame[i] << 8 * ((i - p->check_from) & 3))) & 0xFFFFFFFFUL;
        return (sum & 0xFF) << 24 | (sum & 0xFF00) << 8 | (sum >> 8 & 0xFF00) | sum >> 24;
#endif
#ifdef NMEA_FRAMING_CRC24Q
    case NMEA_CHECKSUM_CRC24Q: /* polynomial 0x1864CFB, initial value 0 */
        for (; i < len; i++) {
            sum ^= (unsigned long)frame[i] << 16;
            for (bit = 0; bit < 8; bit++)
                sum = sum & 0x800000 ? (sum << 1) ^ 0x1864CFB : sum << 1;
        }
        return sum & 0xFFFFFF;
#endif
#ifdef NMEA_FRAMING_CRC16_CCITT
    case NMEA_CHECKSUM_CRC16_CCITT: /* polynomial 0x1021, initial value 0; sent little endian */
        for (; i < len; i++) {
            sum ^= (unsigned long)frame[i] << 8;
            for (bit = 0; bit < 8; bit++)
                sum = sum & 0x8000 ? ((sum << 1) ^ 0x1021) & 0xFFFF : sum << 1 & 0xFFFF;
        }
        return (sum & 0xFF) << 8 | sum >> 8;
#endif
    default:
        return sum;
    }
}

/* Hands on the frame under way as rejected for `error`: its sync bytes. The bytes after them are
   to be read again, before those still to be read again; both lie at the end of f->frame (a frame
   found among them grows from its start and never reaches the byte being read). */
static bool frame_reject(nmea_framer *f, nmea_frame_error error, nmea_framed *out)
{
    size_t sync = FRAMING(f)->sync_len, rest = f->frame_len - sync, i;
    unsigned char *to = f->frame + NMEA_MAX_FRAME - f->replay - rest;
    out->ptr = (const char *)f->frame;
    out->len = sync;
    out->protocol = (nmea_protocol)f->protocol;
    out->error = error;
    out->size = f->frame_size;
    for (i = rest; i > 0; i--) /* to lies after the bytes it takes: from the last on */
        to[i - 1] = f->frame[sync + i - 1];
    f->replay += rest;
    f->frame_len = 0;
    f->frame_size = 0;
    return true;
}

/* A byte of the frame under way, after its first: true when it completes an item (the line before
   the frame, the frame, or what rejects it). */
static bool frame_byte(nmea_framer *f, unsigned char c, nmea_framed *out)
{
    const nmea_framing *p = FRAMING(f);
    bool line = f->frame_len == 1 && framer_end_line(f, out);
    size_t body, i;
    f->frame[f->frame_len++] = c;
    if (f->frame_len == p->header) {
        f->frame_size = frame_size(p, f->frame);
        for (body = p->sync_len; body < f->frame_len && f->frame[body] == 0; body++)
            ;
        if (body == f->frame_len) /* a header of NUL bytes: what a break after a sync makes */
            return frame_reject(f, NMEA_FRAME_NUL_HEADER, out);
        if (f->frame_size > NMEA_MAX_FRAME)
            return frame_reject(f, NMEA_FRAME_TOO_LONG, out);
        if (f->frame_size < p->header + frame_trailer_len(p)) /* a length that counts the whole frame */
            return frame_reject(f, NMEA_FRAME_TOO_SHORT, out);
    }
    if (f->frame_len == f->frame_size) {
        body = f->frame_size - frame_trailer_len(p);
        out->computed = frame_checksum(p, f->frame, body);
        for (i = 0; i < p->end_len; i++)
            out->computed = out->computed << 8 | p->end[i];
        for (out->sent = 0, i = 0; i < p->check_size; i++) /* the checksum, then the end bytes */
            out->sent = out->sent << 8 | f->frame[(p->check_at ? p->check_at : body) + i];
        for (i = 0; i < p->end_len; i++)
            out->sent = out->sent << 8 | f->frame[f->frame_size - p->end_len + i];
        if (out->sent != out->computed)
            return frame_reject(f, NMEA_FRAME_BAD_CHECKSUM, out);
        out->ptr = (const char *)f->frame;
        out->len = f->frame_size;
        out->protocol = (nmea_protocol)f->protocol;
        out->error = NMEA_FRAME_OK;
        f->frame_len = 0;
        f->frame_size = 0; /* (a smaller frame before the next one's header is in must not end it) */
        return true;
    }
    return line;
}

/* One byte of the stream, or of a rejected frame read again: true when it completes an item. */
static bool framer_byte(nmea_framer *f, char byte, nmea_framed *out)
{
    unsigned char c = (unsigned char)byte;
    if (f->frame_len == 1 && (f->protocol = (unsigned char)frame_protocol(f->frame[0], c)) == 0) {
        f->frame_len = 0; /* no frame: its first byte is one of the line (and ends none) */
        (void)framer_line_byte(f, (char)f->frame[0], out);
    }
    if (f->frame_len > 0)
        return frame_byte(f, c, out);
    if (LINE_BOUNDARY[c] == 4 && f->tag == FRAMER_OUTSIDE) {
        framer_resume(f); /* a '$' handed on last starts the line the frame may end */
        f->frame[0] = c;
        f->frame_len = 1;
        /* a '$' ends the line under way whether it starts a frame or a sentence */
        return c == '$' && framer_end_line(f, out);
    }
    return framer_line_byte(f, byte, out);
}

bool nmea_framer_next(nmea_framer *f, nmea_framed *out)
{
    while (f->replay > 0)
        if (framer_byte(f, (char)f->frame[NMEA_MAX_FRAME - f->replay--], out))
            return true;
    return false;
}
#endif

bool nmea_framer_push(nmea_framer *f, const char **data, size_t *len, nmea_framed *out)
{
    const char *p, *end, *q;
    unsigned boundary = 0;
#ifndef NMEA_NO_BINARY_FRAMES
    if (nmea_framer_next(f, out))
        return true;
    for (;;) {
        while (f->frame_len > 0 && *len > 0) { /* a frame under way takes its bytes one by one */
            (*len)--;
            if (framer_byte(f, *(*data)++, out))
                return true;
        }
#endif
        if (*len == 0)
            return false;
        framer_resume(f);
        p = *data;
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
            q = framer_scan(f, p, end, 0, &boundary);
            if (q < end && boundary != FRAMER_SYNC) {
                framed_line(out, p, (size_t)(q - p));
                f->tag = FRAMER_OUTSIDE;
                q += boundary == 1; /* a '$' or '!' stays for the next line */
                *data = q;
                *len = (size_t)(end - q);
                return true;
            }
        } else {
            q = framer_scan(f, p, end, f->length, &boundary);
            if (q < end && boundary != FRAMER_SYNC) {
                framer_keep(f, p, (size_t)(q - p));
                framed_line(out, f->line, f->length);
                f->length = 0;
                f->tag = FRAMER_OUTSIDE;
                q += boundary == 1;
                *data = q;
                *len = (size_t)(end - q);
                return true;
            }
        }
        framer_keep(f, p, (size_t)(q - p));
        *data = q;
        *len = (size_t)(end - q);
#ifndef NMEA_NO_BINARY_FRAMES
        if (q < end) { /* a first sync byte: the line so far is kept, the frame starts */
            (*len)--;
            if (framer_byte(f, *(*data)++, out)) /* ('$': after the line it ends) */
                return true;
        }
    }
#endif
    return false;
}

bool nmea_framer_feed(nmea_framer *f, char byte, nmea_framed *out)
{
#ifndef NMEA_NO_BINARY_FRAMES
    return framer_byte(f, byte, out);
#else
    return framer_line_byte(f, byte, out);
#endif
}

bool nmea_framer_end(nmea_framer *f, nmea_framed *out)
{
#ifndef NMEA_NO_BINARY_FRAMES
    while (f->frame_len > 0 || f->replay > 0) {
        if (nmea_framer_next(f, out))
            return true;
        if (f->frame_len == 1) {
            f->frame_len = 0; /* a lone first sync byte: a byte of the line */
            (void)framer_line_byte(f, (char)f->frame[0], out);
        } else if (f->frame_len > 1) {
            return frame_reject(f, NMEA_FRAME_CUT, out);
        }
    }
#endif
    return framer_end_line(f, out);
}
