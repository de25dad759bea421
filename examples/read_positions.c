/* read_positions.c - the smallest libbiss program: attach to the BiSS-C
 * master firmware running on an AM335x PRU0 and print each slave's latest
 * position. Build against the installed library:
 *   cc read_positions.c $(pkg-config --cflags --libs libbiss)
 * usage: read_positions [MEM]   (MEM: /dev/mem, or a file standing in for it)
 * Errors are the library's words: biss_strerror() and, for open, the detail
 * (path, errno, a hint) libbiss writes into errbuf. */
#include <libbiss.h>
#include <stdio.h>

int main(int argc, char **argv) {
    if (argc > 2) {
        fprintf(stderr, "read_positions: one MEM at most\nusage: read_positions [MEM]\n");
        return 2;
    }
    char detail[512] = "";
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.target = BISS_TARGET_AM335X;
    p.loader = BISS_LOADER_DEVMEM;
    p.devmem = argc > 1 ? argv[1] : NULL;
    p.attach = true; /* use the firmware and configuration in force */
    p.errbuf = detail;
    p.errbuf_len = sizeof detail;
    biss_t *h;
    int rc = biss_open(&p, &h);
    if (rc != BISS_OK) {
        fprintf(stderr, "read_positions: %s%s%s\n", biss_strerror(rc), *detail ? ": " : "", detail);
        return 1;
    }
    struct biss_sample s;
    rc = biss_read_sample(h, &s);
    for (unsigned i = 0; rc == BISS_OK && i < s.nslaves; i++) {
        printf("slave %u: position %llu\n", i, (unsigned long long)s.slave[i].position);
    }
    if (rc != BISS_OK) { /* data RAM held what the firmware never writes: what */
        fprintf(stderr, "read_positions: %s%s%s\n", biss_strerror(rc),
                rc == BISS_E_SHM_RESULT ? ": " : "",
                rc == BISS_E_SHM_RESULT ? biss_shm_problem(h) : "");
    }
    biss_close(h);
    return rc == BISS_OK ? 0 : 1;
}
