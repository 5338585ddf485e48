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

#ifdef NMEA_FRAMING_CRC24Q
/* CRC-24Q of each byte value alone (polynomial 0x1864CFB, initial value 0), the bits of a byte
   eight at a time: RTCM 3 frames are checked a table lookup a byte (1 KB of flash) rather than
   eight steps of a branch (test_runtime.c checks the table against the bitwise definition). */
static const uint32_t FRAME_CRC24Q[256] = {
    0x000000, 0x864CFB, 0x8AD50D, 0x0C99F6, 0x93E6E1, 0x15AA1A, 0x1933EC, 0x9F7F17,
    0xA18139, 0x27CDC2, 0x2B5434, 0xAD18CF, 0x3267D8, 0xB42B23, 0xB8B2D5, 0x3EFE2E,
    0xC54E89, 0x430272, 0x4F9B84, 0xC9D77F, 0x56A868, 0xD0E493, 0xDC7D65, 0x5A319E,
    0x64CFB0, 0xE2834B, 0xEE1ABD, 0x685646, 0xF72951, 0x7165AA, 0x7DFC5C, 0xFBB0A7,
    0x0CD1E9, 0x8A9D12, 0x8604E4, 0x00481F, 0x9F3708, 0x197BF3, 0x15E205, 0x93AEFE,
    0xAD50D0, 0x2B1C2B, 0x2785DD, 0xA1C926, 0x3EB631, 0xB8FACA, 0xB4633C, 0x322FC7,
    0xC99F60, 0x4FD39B, 0x434A6D, 0xC50696, 0x5A7981, 0xDC357A, 0xD0AC8C, 0x56E077,
    0x681E59, 0xEE52A2, 0xE2CB54, 0x6487AF, 0xFBF8B8, 0x7DB443, 0x712DB5, 0xF7614E,
    0x19A3D2, 0x9FEF29, 0x9376DF, 0x153A24, 0x8A4533, 0x0C09C8, 0x00903E, 0x86DCC5,
    0xB822EB, 0x3E6E10, 0x32F7E6, 0xB4BB1D, 0x2BC40A, 0xAD88F1, 0xA11107, 0x275DFC,
    0xDCED5B, 0x5AA1A0, 0x563856, 0xD074AD, 0x4F0BBA, 0xC94741, 0xC5DEB7, 0x43924C,
    0x7D6C62, 0xFB2099, 0xF7B96F, 0x71F594, 0xEE8A83, 0x68C678, 0x645F8E, 0xE21375,
    0x15723B, 0x933EC0, 0x9FA736, 0x19EBCD, 0x8694DA, 0x00D821, 0x0C41D7, 0x8A0D2C,
    0xB4F302, 0x32BFF9, 0x3E260F, 0xB86AF4, 0x2715E3, 0xA15918, 0xADC0EE, 0x2B8C15,
    0xD03CB2, 0x567049, 0x5AE9BF, 0xDCA544, 0x43DA53, 0xC596A8, 0xC90F5E, 0x4F43A5,
    0x71BD8B, 0xF7F170, 0xFB6886, 0x7D247D, 0xE25B6A, 0x641791, 0x688E67, 0xEEC29C,
    0x3347A4, 0xB50B5F, 0xB992A9, 0x3FDE52, 0xA0A145, 0x26EDBE, 0x2A7448, 0xAC38B3,
    0x92C69D, 0x148A66, 0x181390, 0x9E5F6B, 0x01207C, 0x876C87, 0x8BF571, 0x0DB98A,
    0xF6092D, 0x7045D6, 0x7CDC20, 0xFA90DB, 0x65EFCC, 0xE3A337, 0xEF3AC1, 0x69763A,
    0x578814, 0xD1C4EF, 0xDD5D19, 0x5B11E2, 0xC46EF5, 0x42220E, 0x4EBBF8, 0xC8F703,
    0x3F964D, 0xB9DAB6, 0xB54340, 0x330FBB, 0xAC70AC, 0x2A3C57, 0x26A5A1, 0xA0E95A,
    0x9E1774, 0x185B8F, 0x14C279, 0x928E82, 0x0DF195, 0x8BBD6E, 0x872498, 0x016863,
    0xFAD8C4, 0x7C943F, 0x700DC9, 0xF64132, 0x693E25, 0xEF72DE, 0xE3EB28, 0x65A7D3,
    0x5B59FD, 0xDD1506, 0xD18CF0, 0x57C00B, 0xC8BF1C, 0x4EF3E7, 0x426A11, 0xC426EA,
    0x2AE476, 0xACA88D, 0xA0317B, 0x267D80, 0xB90297, 0x3F4E6C, 0x33D79A, 0xB59B61,
    0x8B654F, 0x0D29B4, 0x01B042, 0x87FCB9, 0x1883AE, 0x9ECF55, 0x9256A3, 0x141A58,
    0xEFAAFF, 0x69E604, 0x657FF2, 0xE33309, 0x7C4C1E, 0xFA00E5, 0xF69913, 0x70D5E8,
    0x4E2BC6, 0xC8673D, 0xC4FECB, 0x42B230, 0xDDCD27, 0x5B81DC, 0x57182A, 0xD154D1,
    0x26359F, 0xA07964, 0xACE092, 0x2AAC69, 0xB5D37E, 0x339F85, 0x3F0673, 0xB94A88,
    0x87B4A6, 0x01F85D, 0x0D61AB, 0x8B2D50, 0x145247, 0x921EBC, 0x9E874A, 0x18CBB1,
    0xE37B16, 0x6537ED, 0x69AE1B, 0xEFE2E0, 0x709DF7, 0xF6D10C, 0xFA48FA, 0x7C0401,
    0x42FA2F, 0xC4B6D4, 0xC82F22, 0x4E63D9, 0xD11CCE, 0x575035, 0x5BC9C3, 0xDD8538,
};
#endif

#ifdef NMEA_FRAMING_CRC32
/* The CRC-32 of each byte value (reflected polynomial 0xEDB88320). */
static const unsigned long FRAME_CRC32[256] = {
    0x00000000UL, 0x77073096UL, 0xEE0E612CUL, 0x990951BAUL, 0x076DC419UL, 0x706AF48FUL,
    0xE963A535UL, 0x9E6495A3UL, 0x0EDB8832UL, 0x79DCB8A4UL, 0xE0D5E91EUL, 0x97D2D988UL,
    0x09B64C2BUL, 0x7EB17CBDUL, 0xE7B82D07UL, 0x90BF1D91UL, 0x1DB71064UL, 0x6AB020F2UL,
    0xF3B97148UL, 0x84BE41DEUL, 0x1ADAD47DUL, 0x6DDDE4EBUL, 0xF4D4B551UL, 0x83D385C7UL,
    0x136C9856UL, 0x646BA8C0UL, 0xFD62F97AUL, 0x8A65C9ECUL, 0x14015C4FUL, 0x63066CD9UL,
    0xFA0F3D63UL, 0x8D080DF5UL, 0x3B6E20C8UL, 0x4C69105EUL, 0xD56041E4UL, 0xA2677172UL,
    0x3C03E4D1UL, 0x4B04D447UL, 0xD20D85FDUL, 0xA50AB56BUL, 0x35B5A8FAUL, 0x42B2986CUL,
    0xDBBBC9D6UL, 0xACBCF940UL, 0x32D86CE3UL, 0x45DF5C75UL, 0xDCD60DCFUL, 0xABD13D59UL,
    0x26D930ACUL, 0x51DE003AUL, 0xC8D75180UL, 0xBFD06116UL, 0x21B4F4B5UL, 0x56B3C423UL,
    0xCFBA9599UL, 0xB8BDA50FUL, 0x2802B89EUL, 0x5F058808UL, 0xC60CD9B2UL, 0xB10BE924UL,
    0x2F6F7C87UL, 0x58684C11UL, 0xC1611DABUL, 0xB6662D3DUL, 0x76DC4190UL, 0x01DB7106UL,
    0x98D220BCUL, 0xEFD5102AUL, 0x71B18589UL, 0x06B6B51FUL, 0x9FBFE4A5UL, 0xE8B8D433UL,
    0x7807C9A2UL, 0x0F00F934UL, 0x9609A88EUL, 0xE10E9818UL, 0x7F6A0DBBUL, 0x086D3D2DUL,
    0x91646C97UL, 0xE6635C01UL, 0x6B6B51F4UL, 0x1C6C6162UL, 0x856530D8UL, 0xF262004EUL,
    0x6C0695EDUL, 0x1B01A57BUL, 0x8208F4C1UL, 0xF50FC457UL, 0x65B0D9C6UL, 0x12B7E950UL,
    0x8BBEB8EAUL, 0xFCB9887CUL, 0x62DD1DDFUL, 0x15DA2D49UL, 0x8CD37CF3UL, 0xFBD44C65UL,
    0x4DB26158UL, 0x3AB551CEUL, 0xA3BC0074UL, 0xD4BB30E2UL, 0x4ADFA541UL, 0x3DD895D7UL,
    0xA4D1C46DUL, 0xD3D6F4FBUL, 0x4369E96AUL, 0x346ED9FCUL, 0xAD678846UL, 0xDA60B8D0UL,
    0x44042D73UL, 0x33031DE5UL, 0xAA0A4C5FUL, 0xDD0D7CC9UL, 0x5005713CUL, 0x270241AAUL,
    0xBE0B1010UL, 0xC90C2086UL, 0x5768B525UL, 0x206F85B3UL, 0xB966D409UL, 0xCE61E49FUL,
    0x5EDEF90EUL, 0x29D9C998UL, 0xB0D09822UL, 0xC7D7A8B4UL, 0x59B33D17UL, 0x2EB40D81UL,
    0xB7BD5C3BUL, 0xC0BA6CADUL, 0xEDB88320UL, 0x9ABFB3B6UL, 0x03B6E20CUL, 0x74B1D29AUL,
    0xEAD54739UL, 0x9DD277AFUL, 0x04DB2615UL, 0x73DC1683UL, 0xE3630B12UL, 0x94643B84UL,
    0x0D6D6A3EUL, 0x7A6A5AA8UL, 0xE40ECF0BUL, 0x9309FF9DUL, 0x0A00AE27UL, 0x7D079EB1UL,
    0xF00F9344UL, 0x8708A3D2UL, 0x1E01F268UL, 0x6906C2FEUL, 0xF762575DUL, 0x806567CBUL,
    0x196C3671UL, 0x6E6B06E7UL, 0xFED41B76UL, 0x89D32BE0UL, 0x10DA7A5AUL, 0x67DD4ACCUL,
    0xF9B9DF6FUL, 0x8EBEEFF9UL, 0x17B7BE43UL, 0x60B08ED5UL, 0xD6D6A3E8UL, 0xA1D1937EUL,
    0x38D8C2C4UL, 0x4FDFF252UL, 0xD1BB67F1UL, 0xA6BC5767UL, 0x3FB506DDUL, 0x48B2364BUL,
    0xD80D2BDAUL, 0xAF0A1B4CUL, 0x36034AF6UL, 0x41047A60UL, 0xDF60EFC3UL, 0xA867DF55UL,
    0x316E8EEFUL, 0x4669BE79UL, 0xCB61B38CUL, 0xBC66831AUL, 0x256FD2A0UL, 0x5268E236UL,
    0xCC0C7795UL, 0xBB0B4703UL, 0x220216B9UL, 0x5505262FUL, 0xC5BA3BBEUL, 0xB2BD0B28UL,
    0x2BB45A92UL, 0x5CB36A04UL, 0xC2D7FFA7UL, 0xB5D0CF31UL, 0x2CD99E8BUL, 0x5BDEAE1DUL,
    0x9B64C2B0UL, 0xEC63F226UL, 0x756AA39CUL, 0x026D930AUL, 0x9C0906A9UL, 0xEB0E363FUL,
    0x72076785UL, 0x05005713UL, 0x95BF4A82UL, 0xE2B87A14UL, 0x7BB12BAEUL, 0x0CB61B38UL,
    0x92D28E9BUL, 0xE5D5BE0DUL, 0x7CDCEFB7UL, 0x0BDBDF21UL, 0x86D3D2D4UL, 0xF1D4E242UL,
    0x68DDB3F8UL, 0x1FDA836EUL, 0x81BE16CDUL, 0xF6B9265BUL, 0x6FB077E1UL, 0x18B74777UL,
    0x88085AE6UL, 0xFF0F6A70UL, 0x66063BCAUL, 0x11010B5CUL, 0x8F659EFFUL, 0xF862AE69UL,
    0x616BFFD3UL, 0x166CCF45UL, 0xA00AE278UL, 0xD70DD2EEUL, 0x4E048354UL, 0x3903B3C2UL,
    0xA7672661UL, 0xD06016F7UL, 0x4969474DUL, 0x3E6E77DBUL, 0xAED16A4AUL, 0xD9D65ADCUL,
    0x40DF0B66UL, 0x37D83BF0UL, 0xA9BCAE53UL, 0xDEBB9EC5UL, 0x47B2CF7FUL, 0x30B5FFE9UL,
    0xBDBDF21CUL, 0xCABAC28AUL, 0x53B39330UL, 0x24B4A3A6UL, 0xBAD03605UL, 0xCDD70693UL,
    0x54DE5729UL, 0x23D967BFUL, 0xB3667A2EUL, 0xC4614AB8UL, 0x5D681B02UL, 0x2A6F2B94UL,
    0xB40BBE37UL, 0xC30C8EA1UL, 0x5A05DF1BUL, 0x2D02EF8DUL,
};
#endif

/* The checksum of a frame's `len` bytes before its checksum, as it is sent read as a big-endian
   number (each kind of nmea_checksum_kind that a protocol of the build uses). */
static unsigned long frame_checksum(const nmea_framing *p, const unsigned char *frame, size_t len)
{
    unsigned long sum = 0;
    size_t i = p->check_from;
#ifdef NMEA_FRAMING_CRC16_CCITT
    unsigned bit;
#endif
    switch (p->checksum) {
#ifdef NMEA_FRAMING_FLETCHER8
    case NMEA_CHECKSUM_FLETCHER8: { /* the sums wrap modulo a power of two of at least 256: masked
                                       once; four bytes a step, B taking A's four running values at once */
        unsigned a = 0, b = 0;
        for (; i + 4 <= len; i += 4) {
            unsigned x0 = frame[i], x1 = frame[i + 1], x2 = frame[i + 2], x3 = frame[i + 3];
            b += 4 * a + 4 * x0 + 3 * x1 + 2 * x2 + x3;
            a += x0 + x1 + x2 + x3;
        }
        for (; i < len; i++) {
            a += frame[i];
            b += a;
        }
        return (unsigned long)(a & 0xFF) << 8 | (b & 0xFF);
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
    case NMEA_CHECKSUM_CRC24Q: /* polynomial 0x1864CFB, initial value 0: a byte a lookup */
        for (; i < len; i++)
            sum = (sum << 8 & 0xFFFFFF) ^ FRAME_CRC24Q[(sum >> 16 ^ frame[i]) & 0xFF];
        return sum;
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
#ifdef NMEA_FRAMING_CRC32
    case NMEA_CHECKSUM_CRC32: /* reflected 0xEDB88320, initial value 0, no final inversion: a byte a
                                 lookup; sent little endian */
        for (; i < len; i++)
            sum = sum >> 8 ^ FRAME_CRC32[(sum ^ frame[i]) & 0xFF];
        return (sum & 0xFF) << 24 | (sum & 0xFF00) << 8 | (sum >> 8 & 0xFF00) | sum >> 24;
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

static bool framer_byte(nmea_framer *f, char byte, nmea_framed *out);

/* The sync bytes so far of a frame that turns out to be none (a third sync byte that does not
   follow, or the stream's end): bytes of the line, as a first sync byte that no second follows
   (the generator keeps line and sync bytes out of a three-byte sync's second). */
static void frame_unstart(nmea_framer *f, nmea_framed *out)
{
    size_t i, n = f->frame_len;
    f->frame_len = 0;
    for (i = 0; i < n; i++)
        (void)framer_line_byte(f, (char)f->frame[i], out);
}

/* A byte of the frame under way, after its first: true when it completes an item (the line before
   the frame, once its sync is whole; the frame, or what rejects it). */
static bool frame_byte(nmea_framer *f, unsigned char c, nmea_framed *out)
{
    const nmea_framing *p = FRAMING(f);
    bool line = false;
    size_t body, i;
    if (f->frame_len < 3) { /* the sync's bytes (one test a byte after them, as before three-byte syncs) */
        if (f->frame_len == 2 && p->sync_len > 2 && c != p->sync[2]) { /* a third sync byte, checked as it comes */
            frame_unstart(f, out);
            return framer_byte(f, (char)c, out); /* (it starts no frame whose third byte it is) */
        }
        line = f->frame_len + 1 == (p->sync_len > 2 ? 3u : 2u) && framer_end_line(f, out);
    }
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
        while (f->frame_len > 0 && *len > 0) { /* a frame under way takes its bytes */
            if (f->frame_len > 1 && f->frame_len >= FRAMING(f)->header && f->frame_size > f->frame_len + 1) {
                /* its length known: the bytes before its last in bulk (frame_byte only stores
                   them), the last one through frame_byte, which checks the frame */
                size_t n = f->frame_size - f->frame_len - 1;
                if (n > *len)
                    n = *len;
                memcpy(f->frame + f->frame_len, *data, n);
                f->frame_len += n;
                *data += n;
                *len -= n;
                if (*len == 0)
                    break;
            }
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
        if (f->frame_len == 1 || (f->frame_len > 1 && f->frame_len < FRAMING(f)->sync_len)) {
            frame_unstart(f, out); /* a sync cut short by the end: bytes of the line */
        } else if (f->frame_len > 1) {
            return frame_reject(f, NMEA_FRAME_CUT, out);
        }
    }
#endif
    return framer_end_line(f, out);
}
