/* What every piece uses: the linkage macros (everything is static, and the generated code in the
   same nmea.c is its only user: NMEA_INTERNAL for what some specs leave unused, NMEA_INLINE for
   a small helper a subset may leave unused (clang warns of an unused static inline), NMEA_HOT,
   NMEA_RARE and NMEA_OUTLINE for the compiler's inlining, NMEA_OUTLINE also for what a subset may
   leave unused), the character classes, hex digits, powers of ten, and nmea_text with the
   comparisons of texts the pieces make. */

#include <string.h>

#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__) /* -Os: the compiler's choices, for size */
#define NMEA_INTERNAL static __attribute__((unused))
#define NMEA_RARE static __attribute__((noinline, cold))
#define NMEA_HOT static inline __attribute__((unused))
#define NMEA_INLINE static inline __attribute__((unused))
#define NMEA_OUTLINE static __attribute__((noinline, unused))
#define NMEA_FRAME static __attribute__((noinline, unused))
#define NMEA_HOT_FRAME static __attribute__((noinline, unused))
#define NMEA_LEAF static inline __attribute__((always_inline, unused))
#define NMEA_RARE_LEAF NMEA_LEAF
#elif defined(__GNUC__)
#define NMEA_INTERNAL static __attribute__((unused))
#define NMEA_RARE static __attribute__((noinline, cold)) /* off the hot path */
#define NMEA_HOT static inline __attribute__((always_inline, unused)) /* a few instructions per byte or field */
#define NMEA_INLINE static inline __attribute__((unused))
#define NMEA_OUTLINE static __attribute__((noinline, unused))
#define NMEA_FRAME static __attribute__((unused))
#define NMEA_HOT_FRAME NMEA_HOT
#define NMEA_LEAF static __attribute__((unused))
#define NMEA_RARE_LEAF NMEA_RARE
#else
#define NMEA_INTERNAL static
#define NMEA_RARE static
#define NMEA_HOT static
#define NMEA_INLINE static inline
#define NMEA_OUTLINE static
#define NMEA_FRAME static
#define NMEA_HOT_FRAME static
#define NMEA_LEAF static
#define NMEA_RARE_LEAF static
#endif
/* NMEA_FRAME, NMEA_HOT_FRAME: a function of nmea_parse's descent kept out of line at -Os (a
   microcontroller's build), where its frame would otherwise be merged into its caller's and the
   deepest path would hold the locals of every field type's reader at once; otherwise as
   NMEA_INTERNAL and NMEA_HOT. NMEA_LEAF: inlined at -Os, so that it adds no frame of its own to
   that descent; otherwise the compiler's choice (NMEA_RARE_LEAF: NMEA_RARE). */

/* The texts only errors use: message patterns, field ids, what a field takes. A firmware short of
   flash builds with -DNMEA_TERSE_ERRORS (and -DNMEA_NO_JSON, whose keys are field ids): an error
   then says its kind, address and wire field (nmea_error.field), its message is empty. */
#ifdef NMEA_TERSE_ERRORS
#ifndef NMEA_NO_JSON
#error "NMEA_TERSE_ERRORS needs NMEA_NO_JSON: the JSON's keys are the field ids it leaves out"
#endif
#define ERROR_TEXT(text) NULL
#else
#define ERROR_TEXT(text) text
#endif

/* The tools' JSON carries a line's TAG blocks: a build without them has none. */
#if defined(NMEA_NO_TAG_BLOCKS) && !defined(NMEA_NO_JSON)
#error "NMEA_NO_TAG_BLOCKS needs NMEA_NO_JSON: the tools' JSON carries the TAG blocks it leaves out"
#endif

static const char HEX_UPPER[] = "0123456789ABCDEF";
static const char HEX_LOWER[] = "0123456789abcdef";

/* 10^k for k from 0 to NMEA_MAX_DIGITS: a table, or in a build for size (-Os) a loop, which
   takes a few instructions of flash where the table takes 152 bytes. */
#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__)
NMEA_INTERNAL int64_t pow10_of(unsigned k)
{
    int64_t p = 1;
    while (k--)
        p *= 10;
    return p;
}
#define POW10(k) pow10_of((unsigned)(k))
#else
static const int64_t POW10_TABLE[NMEA_MAX_DIGITS + 1] = {
    1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000, 1000000000,
    10000000000, 100000000000, 1000000000000, 10000000000000, 100000000000000,
    1000000000000000, 10000000000000000, 100000000000000000, 1000000000000000000,
};
#define POW10(k) POW10_TABLE[k]
#endif

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
NMEA_INLINE bool integer_is(nmea_number n, int64_t v)
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
    size_t k;
    for (k = 0; k < t.len && s[k] && ascii_upper(t.ptr[k]) == s[k]; k++)
        continue;
    return k == t.len && s[k] == 0;
}

/* Whether two words are equal (byte by byte, as text_is: a firmware then links no strcmp). */
static bool words_equal(const char *a, const char *b)
{
    for (; *a && *a == *b; a++, b++)
        continue;
    return *a == *b;
}
