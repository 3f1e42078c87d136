/* The browser build's entry (docs/web.md): the page (web/page.js) calls
 * main with the arguments of `pelt view`; the viewer's frames go on in the
 * page's animation frames after main returns. */
#include "apps/cli.h"

int main(int argc, char **argv) { return cmd_view(argc - 1, argv + 1); }
