/* The AIS messages (nmea_ais.c) against generated/vectors/ais.jsonl, which the Python codec
   decodes and encodes too: every payload decodes to the same JSON as Python's or fails with the
   same error kind, and encodes back to the same armored characters and fill bits.
   Usage: test_ais path/to/ais.jsonl */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nmea_ais.h"

/* The text of a member of a JSON record into `out` (a string's without its quotes). */
static void member(const char *record, const char *key, char *out, size_t cap)
{
    char pattern[64];
    const char *start;
    size_t len;
    snprintf(pattern, sizeof pattern, "\"%s\":", key);
    start = strstr(record, pattern);
    out[0] = '\0';
    if (!start)
        return;
    start += strlen(pattern);
    if (*start == '"')
        start++;
    len = strcspn(start, "\",}");
    if (len >= cap)
        len = cap - 1;
    memcpy(out, start, len);
    out[len] = '\0';
}

int main(int argc, char **argv)
{
    static char record[8192], json[8192];
    char payload[512], fill[8], error[32];
    int decoded = 0, refused = 0, failed = 0;
    FILE *file = argc > 1 ? fopen(argv[1], "r") : NULL;
    if (!file) {
        fprintf(stderr, "usage: test_ais ais.jsonl\n");
        return 2;
    }
    while (fgets(record, sizeof record, file)) {
        nmea_ais_message message;
        nmea_ais_error err;
        nmea_ais_armored armored;
        unsigned fill_bits;
        const char *decode;
        bool ok;
        record[strcspn(record, "\n")] = '\0';
        member(record, "payload", payload, sizeof payload);
        member(record, "fill_bits", fill, sizeof fill);
        member(record, "error", error, sizeof error);
        fill_bits = (unsigned)atoi(fill);
        ok = nmea_ais_decode(payload, strlen(payload), fill_bits, &message, &err);
        if (error[0]) {
            if (ok || strcmp(nmea_ais_error_kind_name(err.kind), error) != 0) {
                printf("FAIL error %s: %s\n", ok ? "none" : nmea_ais_error_kind_name(err.kind), record);
                failed++;
            }
            refused++;
            continue;
        }
        if (!ok) {
            printf("FAIL %s: %s\n", err.message, record);
            failed++;
            continue;
        }
        nmea_ais_json(&message, fill_bits, json, sizeof json);
        decode = strstr(record, "\"decode\":") + 9;
        if (strncmp(json, decode, strlen(decode) - 1) != 0 || strlen(json) != strlen(decode) - 1) {
            printf("FAIL json\n  got  %s\n  want %.*s\n", json, (int)strlen(decode) - 1, decode);
            failed++;
        }
        if (!nmea_ais_encode(&message, &armored, &err) || strcmp(armored.chars, payload) != 0 ||
            armored.fill_bits != fill_bits) {
            printf("FAIL encode %s,%u: %s\n", armored.chars, armored.fill_bits, record);
            failed++;
        }
        decoded++;
    }
    fclose(file);
    printf("%d decoded, %d refused, %d failed\n", decoded, refused, failed);
    return failed || decoded != 44 || refused != 6;
}
