/* libFuzzer target of the C UBX pair (generated/c/nmea_ubx.c): an input is a class, an id and a
   payload. Whatever it holds, decoding reads no byte outside it; a payload that decodes prints its
   JSON (into a buffer large enough and one too small), encodes back to the frame of the same
   bytes, and is refused, writing nothing past it, by a buffer one byte short. `make fuzz-c-ubx`
   (seeds: every UBX frame of tests/data/ubx and tests/data/rtcm3). */

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "nmea_ubx.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static nmea_ubx_message message;
    static uint8_t frame[0xFFFF + NMEA_UBX_OVERHEAD];
    static char json[1 << 18];
    nmea_ubx_error err;
    size_t n;
    if (size < 2 || size - 2 > 0xFFFF)
        return 0;
    if (!nmea_ubx_decode(data[0], data[1], data + 2, size - 2, &message, &err)) {
        if (!err.field && err.kind != NMEA_UBX_BAD_VALUE)
            abort(); /* a refused payload names its field */
        return 0;
    }
    nmea_ubx_json(&message, json, sizeof json);
    nmea_ubx_json(&message, json, 7);
    n = nmea_ubx_encode(&message, frame, sizeof frame, &err);
    if (n != size + 6 || frame[2] != data[0] || frame[3] != data[1] || memcmp(frame + 6, data + 2, size - 2) != 0)
        abort();
    frame[n - 1] ^= 0xFF;
    if (nmea_ubx_encode(&message, frame, n - 1, &err) != 0 || err.kind != NMEA_UBX_NO_ROOM)
        abort();
    return 0;
}
