/* icshadow/json_text.h — JSON text as the library and its tools write it (the lights file, the
 * plan, the render summary, the CLI's JSON outputs): one writer of JSON strings. */
#ifndef ICSHADOW_JSON_TEXT_H
#define ICSHADOW_JSON_TEXT_H

#include <stdio.h>

#include "icshadow/api.h"

#ifdef __cplusplus
extern "C" {
#endif

/* s as a JSON string: quoted, '"' and '\' escaped, control characters as \u00XX; other bytes
 * (UTF-8 included) as they are. */
ICS_API void ics_json_write_string(FILE *f, const char *s);

#ifdef __cplusplus
}
#endif
#endif
