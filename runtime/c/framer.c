/* The stream framer (nmea_framer): bytes as a serial port or socket delivers them, in chunks of
   any size, cut into lines at CR, LF, '$' and '!', an overlong line reported by its length. A
   '\' at the start of a line opens a TAG block, which keeps its sentence: up to the block's
   closing '\' every byte but CR and LF belongs to it, and a '$', '!' or '\' right after that
   continues the line (unless -DNMEA_NO_TAG_BLOCKS: a '\' is then a byte like any other). */

/* The bytes that end a line (CR, LF), start a new one ('$', '!') or open or close a TAG block. */
static const unsigned char LINE_BOUNDARY[256] = {['\r'] = 1, ['\n'] = 1, ['$'] = 2, ['!'] = 2, ['\\'] = 3};

/* Where the line being framed is as to TAG blocks (nmea_framer.tag). */
enum { FRAMER_OUTSIDE, FRAMER_IN_TAG, FRAMER_AFTER_TAG };

void nmea_framer_init(nmea_framer *f)
{
    f->length = 0;
    f->next = 0;
    f->tag = FRAMER_OUTSIDE;
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

/* The first byte from `p` on (the line holding `length` bytes before it) that ends the line or
   starts the next, with *boundary what it is; `end` when none does. */
static const char *framer_scan(nmea_framer *f, const char *p, const char *end, size_t length, unsigned *boundary)
{
    const char *q;
    for (q = p; q < end; q++) {
        if (f->tag == FRAMER_OUTSIDE && !LINE_BOUNDARY[(unsigned char)*q])
            continue; /* the common byte, decided without a call */
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

bool nmea_framer_push(nmea_framer *f, const char **data, size_t *len, nmea_framed *out)
{
    const char *p = *data, *end, *q;
    unsigned boundary = 0;
    if (*len == 0)
        return false;
    framer_resume(f);
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
        if (q < end) {
            out->ptr = (size_t)(q - p) <= NMEA_MAX_LINE ? p : NULL;
            out->len = (size_t)(q - p);
            f->tag = FRAMER_OUTSIDE;
            q += boundary == 1; /* a '$' or '!' stays for the next line */
            *data = q;
            *len = (size_t)(end - q);
            return true;
        }
    } else {
        q = framer_scan(f, p, end, f->length, &boundary);
        framer_keep(f, p, (size_t)(q - p));
        if (q < end) {
            out->ptr = f->length <= NMEA_MAX_LINE ? f->line : NULL;
            out->len = f->length;
            f->length = 0;
            f->tag = FRAMER_OUTSIDE;
            q += boundary == 1;
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

bool nmea_framer_feed(nmea_framer *f, char byte, nmea_framed *out)
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
    out->ptr = f->length <= NMEA_MAX_LINE ? f->line : NULL;
    out->len = f->length;
    f->length = 0;
    f->tag = FRAMER_OUTSIDE;
    f->next = boundary == 2 ? byte : 0; /* the line handed on is still in f->line */
    return true;
}

bool nmea_framer_end(nmea_framer *f, nmea_framed *out)
{
    framer_resume(f);
    f->tag = FRAMER_OUTSIDE;
    if (f->length == 0)
        return false;
    out->ptr = f->length <= NMEA_MAX_LINE ? f->line : NULL;
    out->len = f->length;
    f->length = 0;
    return true;
}
