/* The ceiling of the benchmark: the least work any NMEA parser must do on a line. */
#ifndef BENCH_CEILING_H
#define BENCH_CEILING_H

#include <stddef.h>

/** Most field boundaries ceiling_scan records. */
#define CEILING_MAX_FIELDS 128

/**
 * Checks that `line` (no line ending) is `$...*HH` with the right checksum and records where each
 * field starts: starts[0] is the address, starts[i] the offset after the i-th comma. Converts
 * nothing. Returns the number of fields (address included), or -1 when the line is not framed or
 * its checksum is wrong.
 */
int ceiling_scan(const char *line, size_t len, unsigned short starts[CEILING_MAX_FIELDS]);

#endif
