/* read_positions.c - the smallest libbiss program: attach to the BiSS-C
 * master firmware running on an AM335x PRU0 and print each slave's latest
 * position. Build against the installed library:
 *   cc read_positions.c $(pkg-config --cflags --libs libbiss)
 * usage: read_positions [MEM]   (MEM: /dev/mem, or a file standing in for it) */
#include <libbiss.h>
#include <stdio.h>

int main(int argc, char **argv) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.target = BISS_TARGET_AM335X;
    p.loader = BISS_LOADER_DEVMEM;
    p.devmem = argc > 1 ? argv[1] : NULL;
    p.attach = true; /* use the firmware and configuration in force */
    biss_t *h;
    struct biss_sample s;
    int rc = biss_open(&p, &h);
    if (rc == BISS_OK) {
        rc = biss_read_sample(h, &s);
        for (unsigned i = 0; rc == BISS_OK && i < s.nslaves; i++) {
            printf("slave %u: position %llu\n", i, (unsigned long long)s.slave[i].position);
        }
        biss_close(h);
    }
    if (rc != BISS_OK) {
        fprintf(stderr, "read_positions: %s\n", biss_strerror(rc));
    }
    return rc == BISS_OK ? 0 : 1;
}
