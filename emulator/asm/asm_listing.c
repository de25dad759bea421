/*
 * asm_listing.c - the -L annotated source listing (.txt): every source
 * file with the address and word of the code each line produced, in pasm's
 * layout (including its habit of counting an unwritten word 0 as code of
 * the first file).
 */
#include "asm_ctx.h"

#include <stdlib.h>

struct entry {
    uint32_t line, addr;
};

/* Is address a a code word for the listing? pasm treats an unwritten word 0
 * as written by file 0, line 0. */
static int valid(const struct asm_ctx *c, int a) {
    return a < c->code_offset && (c->info[a].written || a == 0);
}

/* Copy one source line (through its newline) to out; 0 at end of file. */
static int print_line(struct asm_file *f, struct asm_buf *out) {
    for (;;) {
        if (f->pos >= f->len)
            return 0;
        char ch = f->text[f->pos++];
        if (ch == '\r')
            continue;
        asm_buf_put(out, &ch, 1);
        if (ch == '\n') {
            f->line++;
            return 1;
        }
    }
}

static int by_line(const void *pa, const void *pb) {
    const struct entry *a = pa, *b = pb;
    if (a->line != b->line)
        return a->line < b->line ? -1 : 1;
    return a->addr < b->addr ? -1 : a->addr > b->addr;
}

static void list_file(struct asm_ctx *c, struct asm_file *f, struct asm_buf *out) {
    int n = 0;
    struct entry *e = malloc(sizeof *e * (size_t)(c->code_offset > 0 ? c->code_offset : 1));
    if (!e) {
        out->failed = 1;
        return;
    }
    for (int a = 0; a < c->code_offset; a++) {
        if (valid(c, a) && (c->info[a].written ? c->info[a].file : 0) == f->index) {
            e[n].line = c->info[a].written ? c->info[a].line : 0;
            e[n].addr = (uint32_t)a;
            n++;
        }
    }
    qsort(e, (size_t)n, sizeof *e, by_line);
    f->pos = 0;
    f->line = 1;
    if (!n)
        asm_buf_printf(out, "(No Output Generated)\n\n");
    else
        asm_buf_printf(out, "(%d Instructions Generated)\n\n", n);
    int k = 0;
    for (;;) {
        uint32_t cline = f->line;
        int printed = 0;
        while (k < n && e[k].line < cline)
            k++;
        for (; k < n && e[k].line == cline; k++) {
            uint32_t w = c->words[e[k].addr];
            if (!printed) {
                asm_buf_printf(out, "%5u : 0x%04x 0x%08x : ", cline, e[k].addr, w);
                printed = 1;
                if (!print_line(f, out))
                    goto done;
            } else {
                asm_buf_printf(out, "      : 0x%04x 0x%08x : \n", e[k].addr, w);
            }
        }
        if (!printed) {
            asm_buf_printf(out, "%5u :                   : ", f->line);
            if (!print_line(f, out))
                goto done;
        }
    }
done:
    free(e);
}

void asm_source_listing(struct asm_ctx *c, struct asm_buf *out) {
    for (unsigned i = 0; i < c->nfiles; i++) {
        struct asm_file *f = &c->files[i];
        asm_buf_printf(out, "Source File %u : '%s' ", i + 1, f->name);
        if (!f->text) {
            asm_buf_printf(out, "(File Not Found '%s/%s')\n\n", f->dir, f->name);
            continue;
        }
        list_file(c, f, out);
        asm_buf_printf(out, "\n\n");
    }
}
