#include "core/base/error.h"

#include <stdarg.h>
#include <stdio.h>

static const char *const status_text[] = {
#define PELT__TEXT(name, text) text,
    PELT_STATUS_LIST(PELT__TEXT)
#undef PELT__TEXT
};

const char *pelt_status_text(pelt_status status)
{
    if ((unsigned)status >= PELT_STATUS_COUNT) return "unknown status";
    return status_text[status];
}

pelt_status pelt__fail(pelt_error *err, pelt_status status, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        err->status = status;
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return status;
}
