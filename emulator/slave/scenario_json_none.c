/* scenario_json_none.c - scenario files in a build without cJSON (a cross
 * build for a target that has none): refused, naming the file; the named
 * profiles (profiles.c) still work. */
#include "scenario_json.h"

#include <stdio.h>

int scenario_from_json(const char *text, scenario *s, char *err, size_t errlen) {
    (void)text;
    (void)s;
    snprintf(err, errlen, "scenario files need cJSON, which this build was made without");
    return -1;
}

int scenario_load_file(const char *path, scenario *s, char *err, size_t errlen) {
    (void)s;
    snprintf(err, errlen, "%s: scenario files need cJSON, which this build was made without", path);
    return -1;
}
