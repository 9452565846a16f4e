/* A C user linked through pkg-config. */
#include <loopsurf.h>
#include <stdio.h>

int main(void) {
    int major, minor, patch;
    ls_version(&major, &minor, &patch);
    printf("loopsurf %d.%d.%d: %s\n", major, minor, patch, ls_status_string(LS_ERR_BAD_STREAM));
    return major == 0 && minor >= 1 ? 0 : 1;
}
