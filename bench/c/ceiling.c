#include "ceiling.h"

static int hex_digit(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    return -1;
}

int ceiling_scan(const char *line, size_t len, unsigned short starts[CEILING_MAX_FIELDS])
{
    size_t end, i;
    unsigned sum = 0;
    int fields = 1, high, low;

    if (len < 4 || len > 1024 || line[0] != '$' || line[len - 3] != '*')
        return -1;
    end = len - 3;
    starts[0] = 1;
    for (i = 1; i < end; i++) {
        unsigned char c = (unsigned char)line[i];
        sum ^= c;
        if (c == ',') {
            if (fields == CEILING_MAX_FIELDS)
                return -1;
            starts[fields++] = (unsigned short)(i + 1);
        }
    }
    high = hex_digit(line[end + 1]);
    low = hex_digit(line[end + 2]);
    if (high < 0 || low < 0 || (unsigned)(high * 16 + low) != sum)
        return -1;
    return fields;
}
