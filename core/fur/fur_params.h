/* The rows of pelt_fur_desc (pelt/params.h); the checks that read them are
 * core/base/params.h's. */
#ifndef PELT_FUR_PARAMS_H
#define PELT_FUR_PARAMS_H

#include "pelt/fur.h"
#include "pelt/params.h"
#include "core/base/params.h"

#include <stdbool.h>
#include <stddef.h>

#endif
