/* pru-elf - wraps a raw PRU IRAM image (pasm -b / pruasm -b output) into
 * the ELF file Linux's remoteproc driver for the PRU (pru_rproc) loads:
 * ELF32 little-endian, EM_TI_PRU, ET_EXEC, entry 0; the image as an
 * executable PT_LOAD at IRAM address 0 (pru_rproc puts PF_X segments into
 * IRAM, the others into data RAM at their p_paddr, PRU0's own data RAM
 * being device address 0); the identification block and an empty
 * version-1 resource table as a data PT_LOAD at BISS_ID (biss_shm.h), the
 * top of the 4 KB data RAM that the firmware never touches.
 *
 *   pru-elf IMAGE.bin OUT.elf
 *
 * A separate step rather than an output of the assembler: it wraps
 * whatever assembler made the image (pruasm, or TI's pasm with
 * -DBISS_FW_ASSEMBLER=pasm) and keeps libelf out of the assembler. */
#include "biss_image_id.h"
#include "safe_file.h"

#include <errno.h>
#include <fcntl.h>
#include <gelf.h>
#include <libelf.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_IMAGE (12 * 1024) /* the biggest PRU IRAM (AM437x ICSS1) */

static const char shstrtab[] = "\0.text\0.biss_id\0.resource_table\0.shstrtab";
enum { NAME_TEXT = 1, NAME_ID = 7, NAME_RSC = 16, NAME_SHSTRTAB = 32 };

static int fail(const char *path, const char *what) {
    fprintf(stderr, "pru-elf: %s: %s\n", path, what);
    return 1;
}

static int elf_fail(const char *path) {
    return fail(path, elf_errmsg(-1));
}

static uint8_t *read_image(const char *path, size_t *n) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        fail(path, strerror(errno));
        return NULL;
    }
    uint8_t *buf = malloc(MAX_IMAGE + 1);
    size_t got = buf ? fread(buf, 1, MAX_IMAGE + 1, f) : 0;
    int err = ferror(f);
    fclose(f);
    if (!buf || err) {
        free(buf);
        fail(path, buf ? "read error" : "out of memory");
        return NULL;
    }
    if (got == 0 || got % 4 != 0 || got > MAX_IMAGE) {
        free(buf);
        fprintf(
            stderr, "pru-elf: %s: %zu%s bytes: an IRAM image is 4..%d bytes, whole 32-bit words\n",
            path, got > MAX_IMAGE ? (size_t)MAX_IMAGE : got, got > MAX_IMAGE ? "+" : "", MAX_IMAGE);
        return NULL;
    }
    *n = got;
    return buf;
}

static Elf_Scn *add_section(Elf *e, unsigned name, Elf32_Word type, Elf32_Word flags,
                            Elf32_Addr addr, void *data, size_t n) {
    Elf_Scn *s = elf_newscn(e);
    Elf_Data *d = s ? elf_newdata(s) : NULL;
    Elf32_Shdr *sh = s ? elf32_getshdr(s) : NULL;
    if (!d || !sh) {
        return NULL;
    }
    d->d_buf = data;
    d->d_size = n;
    d->d_type = ELF_T_BYTE;
    d->d_align = type == SHT_STRTAB ? 1 : 4;
    d->d_version = EV_CURRENT;
    sh->sh_name = name;
    sh->sh_type = type;
    sh->sh_flags = flags;
    sh->sh_addr = addr;
    sh->sh_addralign = d->d_align;
    return s;
}

/* Builds the ELF in e (opened for writing on an fd). */
static int build(Elf *e, uint8_t *image, size_t n, uint8_t *data) {
    Elf32_Ehdr *eh = elf32_newehdr(e);
    if (!eh) {
        return -1;
    }
    eh->e_ident[EI_DATA] = ELFDATA2LSB;
    eh->e_ident[EI_OSABI] = ELFOSABI_NONE;
    eh->e_type = ET_EXEC;
    eh->e_machine = EM_TI_PRU;
    eh->e_version = EV_CURRENT;
    eh->e_entry = 0;
    Elf32_Phdr *ph = elf32_newphdr(e, 2);
    if (!ph) {
        return -1;
    }
    Elf_Scn *text = add_section(e, NAME_TEXT, SHT_PROGBITS, SHF_ALLOC | SHF_EXECINSTR, 0, image, n);
    Elf_Scn *id = add_section(e, NAME_ID, SHT_PROGBITS, SHF_ALLOC | SHF_WRITE, BISS_ID, data,
                              sizeof(struct biss_shm_id));
    Elf_Scn *rsc = add_section(e, NAME_RSC, SHT_PROGBITS, SHF_ALLOC | SHF_WRITE, BISS_RSC_TABLE,
                               data + sizeof(struct biss_shm_id), BISS_RSC_TABLE_BYTES);
    Elf_Scn *str =
        add_section(e, NAME_SHSTRTAB, SHT_STRTAB, 0, 0, (void *)shstrtab, sizeof shstrtab);
    if (!text || !id || !rsc || !str) {
        return -1;
    }
    eh->e_shstrndx = (Elf32_Half)elf_ndxscn(str);
    /* lay the sections out, then point the segments at them */
    if (elf_update(e, ELF_C_NULL) < 0) {
        return -1;
    }
    ph = elf32_getphdr(e);
    Elf32_Shdr *ts = elf32_getshdr(text), *is = elf32_getshdr(id);
    ph[0] = (Elf32_Phdr){.p_type = PT_LOAD,
                         .p_offset = ts->sh_offset,
                         .p_vaddr = 0,
                         .p_paddr = 0,
                         .p_filesz = (Elf32_Word)n,
                         .p_memsz = (Elf32_Word)n,
                         .p_flags = PF_R | PF_X,
                         .p_align = 4};
    ph[1] = (Elf32_Phdr){.p_type = PT_LOAD,
                         .p_offset = is->sh_offset,
                         .p_vaddr = BISS_ID,
                         .p_paddr = BISS_ID,
                         .p_filesz = BISS_ID_END - BISS_ID,
                         .p_memsz = BISS_ID_END - BISS_ID,
                         .p_flags = PF_R | PF_W,
                         .p_align = 4};
    elf_flagphdr(e, ELF_C_SET, ELF_F_DIRTY);
    return elf_update(e, ELF_C_WRITE) < 0 ? -1 : 0;
}

int main(int argc, char **argv) {
    if (argc == 2 && strcmp(argv[1], "--version") == 0) { /* the project's (CMakeLists.txt) */
        printf("%s %s\n", "pru-elf", BISS_VERSION);
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "--help") == 0) {
        printf("usage: pru-elf IMAGE.bin OUT.elf\n"
               "Writes the raw PRU IRAM image IMAGE.bin (pruasm -b) as the ELF file Linux's\n"
               "PRU remoteproc driver loads; OUT.elf is written whole or not at all.\n"
               "\n"
               "  --help     this text\n"
               "  --version  the version\n"
               "\n"
               "exit status: 0 written, 1 an error (a file, libelf), 2 bad usage\n");
        return 0;
    }
    for (int i = 1; i < argc; i++) {
        if (argv[i][0] == '-' && argv[i][1]) { /* the tools' one form: README "Conventions" */
            fprintf(stderr, "pru-elf: unknown option '%s'\n", argv[i]);
            argc = 0;
            break;
        }
    }
    if (argc != 3) {
        if (argc) {
            fprintf(stderr, "pru-elf: expected IMAGE.bin OUT.elf, not %d arguments\n", argc - 1);
        }
        fprintf(stderr, "Try 'pru-elf --help' for more information.\n");
        return 2;
    }
    const char *in = argv[1], *out = argv[2];
    size_t n;
    uint8_t *image = read_image(in, &n);
    if (!image) {
        return 1;
    }
    /* the two data sections are adjacent: one segment, both in order */
    uint8_t data[BISS_ID_END - BISS_ID];
    struct biss_shm_id ident;
    biss_image_id(image, n, &ident);
    memcpy(data, &ident, sizeof ident);
    biss_rsc_table(data + sizeof ident);
    if (elf_version(EV_CURRENT) == EV_NONE) {
        free(image);
        return elf_fail(out);
    }
    /* written whole or not at all, never over what is not a regular file
     * (safe_file.h) */
    struct safe_file f;
    char err[PATH_MAX + 128];
    if (safe_file_open(&f, out, err, sizeof err) != 0) {
        free(image);
        fprintf(stderr, "pru-elf: %s\n", err);
        return 1;
    }
    Elf *e = elf_begin(fileno(f.f), ELF_C_WRITE, NULL);
    int rc = e ? build(e, image, n, data) : -1;
    if (rc) {
        fail(out, elf_errmsg(-1));
    }
    if (e) {
        elf_end(e);
    }
    free(image);
    if (rc) {
        safe_file_abort(&f);
        return 1;
    }
    if (safe_file_close(&f, err, sizeof err) != 0) {
        fprintf(stderr, "pru-elf: %s\n", err);
        return 1;
    }
    return 0;
}
