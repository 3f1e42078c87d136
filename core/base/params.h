/* Defaults and range checks driven by a desc's rows (pelt/params.h). */
#ifndef PELT_BASE_PARAMS_H
#define PELT_BASE_PARAMS_H

#include "pelt/params.h"

#include <stdbool.h>
#include <stddef.h>

/* The row named `name` among count rows, or NULL. */
const pelt_param *pelt__params_find(const pelt_param *rows, size_t count, const char *name);

/* Puts each row's default where the field is zero (every float of a
 * colour zero); rows whose default is derived are left to the caller. */
void pelt__params_defaults(const pelt_param *rows, size_t count, void *desc);

/* Whether x lies in the row's range (an enum: one of its names). */
bool pelt__param_in_range(const pelt_param *p, double x);

/* The row's range in words, for messages: "a number in (0, 64]". */
void pelt__param_range_text(const pelt_param *p, char *buf, size_t size);

/* Every field of desc in its row's range, else PELT_ERR_INVALID_ARGUMENT
 * naming `what`, the field, the range and the value. Rows with
 * PELT_PARAM_ZERO_OK flags accept 0 (their derived default) too. */
pelt_status pelt__params_check(const pelt_param *rows, size_t count, const void *desc, const char *what,
                               pelt_error *err);

#endif
