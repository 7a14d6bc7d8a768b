/* status.c — messages for ics_status codes, from the one table in icshadow/status.h. */
#include "icshadow/status.h"

const char *ics_status_str(ics_status status) {
  static const char *const messages[] = {
#define ICS_STATUS_MSG_(name, msg) msg,
      ICS_STATUS_LIST(ICS_STATUS_MSG_)
#undef ICS_STATUS_MSG_
  };
  if ((unsigned)status >= (unsigned)ICS_STATUS_COUNT_) return "unknown status";
  return messages[status];
}
