/*
 * asm_dbg.c - the -d debug file for TI's pView debugger: a header, the
 * labels (newest first), the source file names and one record per code
 * word, all little-endian, in the layout pasm 0.87 writes.
 */
#include "asm_ctx.h"

#include <stdio.h>
#include <string.h>

#define DBG_FILE_ID       0x10150003u /* format version 3 */
#define DBG_NAME_LEN      64
#define DBG_HEADER_LEN    36
#define DBG_LABEL_LEN     (4 + DBG_NAME_LEN)
#define DBG_CODE_LEN      16
#define DBG_CODE_FILEINFO 0x01
#define DBG_CODE_CANMAP   0x02

static void put32(struct asm_buf *b, uint32_t v) {
    char p[4] = {(char)v, (char)(v >> 8), (char)(v >> 16), (char)(v >> 24)};
    asm_buf_put(b, p, 4);
}

static void put_name(struct asm_buf *b, const char *s) {
    char name[DBG_NAME_LEN] = {0};
    size_t n = strlen(s);
    memcpy(name, s, n < DBG_NAME_LEN - 1 ? n : DBG_NAME_LEN - 1);
    asm_buf_put(b, name, sizeof name);
}

void asm_debug_file(struct asm_ctx *c, struct asm_buf *b) {
    uint32_t nwords = (uint32_t)c->code_offset;
    uint32_t labels_at = DBG_HEADER_LEN;
    uint32_t files_at = labels_at + (uint32_t)c->nlabels * DBG_LABEL_LEN;
    uint32_t code_at = files_at + c->nfiles * DBG_NAME_LEN;
    put32(b, DBG_FILE_ID);
    put32(b, (uint32_t)c->nlabels);
    put32(b, labels_at);
    put32(b, c->nfiles);
    put32(b, files_at);
    put32(b, nwords);
    put32(b, code_at);
    put32(b, (uint32_t)c->entry_point);
    put32(b, 0); /* flags: little-endian core */

    for (size_t i = c->nlabels; i-- > 0;) {
        uint32_t v = 0;
        asm_label_find(c, c->label_order[i], &v);
        put32(b, v);
        put_name(b, c->label_order[i]);
    }
    for (unsigned i = 0; i < c->nfiles; i++) {
        const struct asm_file *f = &c->files[i];
        char path[ASM_DIR_MAX + ASM_NAME_MAX + 2];
        /* pasm names a file with its directory only when that is short. */
        if (!strcmp(f->dir, ".") || !strcmp(f->dir, "./.") ||
            strlen(f->name) + strlen(f->dir) >= DBG_NAME_LEN)
            snprintf(path, sizeof path, "%s", f->name);
        else
            snprintf(path, sizeof path, "%s/%s", f->dir, f->name);
        put_name(b, path);
    }
    for (uint32_t a = 0; a < nwords; a++) {
        const struct asm_wordinfo *w = &c->info[a];
        char head[4] = {0};
        if (w->written) {
            head[0] = DBG_CODE_FILEINFO | DBG_CODE_CANMAP;
            head[2] = (char)(w->file & 0xff);
            head[3] = (char)(w->file >> 8);
        }
        asm_buf_put(b, head, 4);
        put32(b, w->written ? w->line : 0);
        put32(b, w->written ? a : 0);
        put32(b, c->words[a]);
    }
}
