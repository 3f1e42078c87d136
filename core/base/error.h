/* Private helpers for filling pelt_error. */
#ifndef PELT_ERROR_INTERNAL_H
#define PELT_ERROR_INTERNAL_H

#include "pelt/base.h"

/* Sets err (if not NULL) to status and a printf-formatted message; returns
 * status so callers can write `return pelt__fail(err, ...)`. */
pelt_status pelt__fail(pelt_error *err, pelt_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
