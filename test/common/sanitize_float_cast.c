/* Casts a double beyond an int64_t's range: the sanitizer build
 * (BISS_SANITIZE, float-cast-overflow) stops here with an error, which is
 * what its test expects; without that check the cast passes unseen. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv) {
    (void)argv;
    volatile double far = 1e300 * argc;
    int64_t t = (int64_t)far;
    printf("cast %g to %lld unchecked\n", far, (long long)t);
    return 0;
}
