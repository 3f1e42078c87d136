#include "support/check.h"

int check_failures = 0;
const char *check_current = "";

int check_summary(void)
{
    if (check_failures) fprintf(stderr, "%d check(s) failed\n", check_failures);
    return check_failures ? 1 : 0;
}

int check_skip(const char *reason)
{
    printf("SKIPPED: %s\n", reason);
    return CHECK_SKIP_CODE;
}
