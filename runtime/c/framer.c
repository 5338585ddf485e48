/* The stream framer (nmea_framer): bytes as a serial port or socket delivers them, in chunks of
   any size, cut into lines at CR, LF, '$' and '!', an overlong line reported by its length. */

/* The bytes that end a line (CR, LF) or start a new one ('$', '!'). */
static const unsigned char LINE_BOUNDARY[256] = {['\r'] = 1, ['\n'] = 1, ['$'] = 2, ['!'] = 2};

void nmea_framer_init(nmea_framer *f)
{
    f->length = 0;
    f->next = 0;
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

bool nmea_framer_feed(nmea_framer *f, char byte, nmea_framed *out)
{
    /* as LINE_BOUNDARY says (a firmware that feeds links no table of 256 bytes) */
    unsigned boundary = byte == '\r' || byte == '\n' ? 1 : byte == '$' || byte == '!' ? 2 : 0;
    framer_resume(f);
    if (!boundary || (f->length == 0 && boundary == 2)) {
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
    f->next = boundary == 2 ? byte : 0; /* the line handed on is still in f->line */
    return true;
}

bool nmea_framer_end(nmea_framer *f, nmea_framed *out)
{
    framer_resume(f);
    if (f->length == 0)
        return false;
    out->ptr = f->length <= NMEA_MAX_LINE ? f->line : NULL;
    out->len = f->length;
    f->length = 0;
    return true;
}
