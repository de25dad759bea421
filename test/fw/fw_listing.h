/*
 * fw_listing.h - the firmware's labels and source lines, read from the
 * listing pruasm writes (-l): where each label lies, and which source line
 * each instruction word came from, so that a test finds code by name (not
 * by address) and names the block an address belongs to.
 */
#ifndef FW_LISTING_H
#define FW_LISTING_H

#include <stddef.h>
#include <stdint.h>

struct fw_label {
    char name[64];
    uint32_t pc;   /* word address */
    int in_macro;  /* a label of a macro body (pruasm spells it _NAME_m_k_) */
    char base[64]; /* its name as written: NAME for _NAME_m_k_ */
};

struct fw_listing {
    struct fw_label *labels; /* in address order */
    size_t nlabels;
    /* per word address: the source line that made it (0: none) */
    unsigned *line;
    char (*file)[32];
    size_t nwords;
    /* where the files named in the listing are, for their source text */
    char *src_dir;
    /* the main file's text when it was assembled from memory (else NULL) */
    char *main_text;
    char main_name[32];
};

/* Parses listing text (pruasm_image.listing). src_dir: the directory the
 * listed file names are relative to (for the source text of a line);
 * main_text: the main file's text if it was assembled from memory (NULL:
 * read from src_dir). Returns 0, or -1 with a message in err. */
int fw_listing_parse(struct fw_listing *l, const char *listing, size_t nwords, const char *src_dir,
                     const char *main_text, char *err, size_t errlen);
void fw_listing_free(struct fw_listing *l);

/* The address of a label (by its name as written in the source, outside
 * macros), or -1. */
int32_t fw_label_pc(const struct fw_listing *l, const char *name);
/* The label at exactly this address, or NULL (the first one outside a
 * macro if there are several). */
const struct fw_label *fw_label_at(const struct fw_listing *l, uint32_t pc);

/* "NAME+off in MACRO_LABEL+off (file:line `source text`)" for an address:
 * the nearest label outside macros before it, the nearest macro label if
 * nearer, and the source line (a macro's invocation for its body). */
void fw_describe_pc(const struct fw_listing *l, uint32_t pc, char *buf, size_t len);

#endif
