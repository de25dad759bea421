/* Scenario files: JSON, parsed with cJSON. Every field is optional; the
 * scenario starts from "profile" (default "generic") and each field present
 * replaces the profile's value. Unknown fields are errors, so a typo never
 * goes unnoticed. See MODELS.md for the full list. */
#ifndef SCENARIO_JSON_H
#define SCENARIO_JSON_H

#include "scenario.h"

#include <stddef.h>

/* Parses JSON text into s. Returns 0, or -1 with a message in err naming
 * the field and what is wrong ("biss.slaves[0].crc_poly: expected ..."). */
int scenario_from_json(const char *text, scenario *s, char *err, size_t errlen);

/* Reads and parses a file; errors are prefixed with the path. */
int scenario_load_file(const char *path, scenario *s, char *err, size_t errlen);

#endif
