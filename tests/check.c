#include "check.h"

int check_failures = 0;
const char *check_current = "";

int check_summary(void)
{
    if (check_failures) fprintf(stderr, "%d check(s) failed\n", check_failures);
    return check_failures ? 1 : 0;
}
