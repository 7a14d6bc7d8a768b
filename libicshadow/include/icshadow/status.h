/* icshadow/status.h — status codes returned by every libicshadow function that can fail
 * for a reason other than a math domain (math functions return NaN instead). */
#ifndef ICSHADOW_STATUS_H
#define ICSHADOW_STATUS_H

#include "icshadow/api.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One table of codes and messages (X-macro): ICS_STATUS_ITEM(name, message). */
#define ICS_STATUS_LIST(X)                                                             \
  X(ICS_OK, "success")                                                                 \
  X(ICS_ERR_INVALID_ARG, "invalid argument")                                           \
  X(ICS_ERR_NAN, "argument is NaN")                                                    \
  X(ICS_ERR_NEGATIVE_VARIANCE, "variance is negative")                                 \
  X(ICS_ERR_INFINITE, "argument is infinite")                                          \
  X(ICS_ERR_RANGE, "argument out of range")                                            \
  X(ICS_ERR_NOMEM, "out of memory")                                                    \
  X(ICS_ERR_IO, "input/output error")                                                 \
  X(ICS_ERR_SIZE, "size out of range (empty or too large)")                            \
  X(ICS_ERR_PARSE, "cannot parse input")                                               \
  X(ICS_ERR_UNSUPPORTED, "unsupported option or missing component")

typedef enum ics_status {
#define ICS_STATUS_ENUM_(name, msg) name,
  ICS_STATUS_LIST(ICS_STATUS_ENUM_)
#undef ICS_STATUS_ENUM_
  ICS_STATUS_COUNT_
} ics_status;

/* A static, human-readable message for a status code (never NULL). */
ICS_API const char *ics_status_str(ics_status status);

#ifdef __cplusplus
}
#endif
#endif
