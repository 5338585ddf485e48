/*
 * Runtime (hand-written: runtime/c/): framing, checksum, field types, errors, JSON, and the one
 * reader, writer and JSON form that interpret the layout tables the generator writes.
 *
 * The acceptance rules and messages here are shared byte for byte with the Python and Rust
 * runtimes (see docs/json.md). Everything is static: the generated per-sentence code after it in
 * nmea.c is its only user, and the public functions are declared in nmea.h.
 *
 * This file is the list of the runtime's pieces in the order they are pasted into nmea.c (each
 * uses only those before it, and generated.c declares what the generated code after them
 * defines): the C emitter (generator/emit_c.py) puts each piece in place of its #include, and
 * the runtime's tests include this file as it is.
 */

#include "base.c"
#include "writer.c"
#include "errors.c"
#include "framing.c"
#include "tag_block.c"
#include "framings.c"
#include "framer.c"
#include "field_parse.c"
#include "reader.c"
#include "fast_read.c"
#include "field_write.c"
#include "fast_write.c"
#include "json_write.c"
#include "json_read.c"
#include "json_fields.c"
#include "tables.c"
#include "layout.c"
#include "layout_write.c"
#include "layout_json.c"
#include "generated.c"
#include "dispatch.c"
#include "small.c"
#include "api.c"
#include "values.c"
#include "json_api.c"
#include "fixes.c"
