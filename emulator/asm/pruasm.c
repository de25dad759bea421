/*
 * pruasm.c - the library entry points: two passes over the source (labels
 * from pass 1 serve pass 2), the final checks, and pasm's output formats.
 */
#include "asm_ctx.h"
#include "pru_isa.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* -D equates exist before the source in every pass. */
static void define_cmdline(struct asm_ctx *c) {
    struct asm_file cmdline = {.name = "[CommandLine]", .line = 0};
    const struct pruasm_options *o = c->opt;
    for (size_t i = 0; o && i < o->ndefines; i++) {
        char name[ASM_TOKEN_MAX];
        const char *d = o->defines[i], *eq = strchr(d, '=');
        size_t n = eq ? (size_t)(eq - d) : strlen(d);
        if (n >= sizeof name) {
            asm_report(c, &cmdline, REP_ERROR, "Command line equate name too long");
            continue;
        }
        memcpy(name, d, n);
        name[n] = 0;
        /* pasm keeps "1" when the value after '=' is empty */
        asm_equate_create(c, &cmdline, name, eq && eq[1] ? eq + 1 : "1");
    }
}

static void run_pass(struct asm_ctx *c) {
    c->code_offset = -1;
    c->have_entry = 0;
    c->entry_point = -1;
    define_cmdline(c);
    asm_struct_init(c);
    struct asm_file *f = asm_file_open(c, NULL, c->main_path ? c->main_path : "", 0);
    if (f) {
        asm_process_file(c, f);
        asm_file_close(c, f);
    }
    asm_equate_clear(c);
    asm_struct_clear(c);
    asm_macro_clear(c);
}

static void release(struct asm_ctx *c) {
    for (unsigned i = 0; i < c->nfiles; i++)
        free(c->files[i].text);
    asm_sym_clear(&c->labels, NULL);
    for (size_t i = 0; i < c->nlabels; i++)
        free(c->label_order[i]);
    free(c->label_order);
    asm_buf_free(&c->listing);
    free(c);
}

static int fill_image(struct asm_ctx *c, struct pruasm_image *out) {
    size_t n = (size_t)c->code_offset;
    out->words = malloc(n * sizeof *out->words);
    if (!out->words)
        return -1;
    memcpy(out->words, c->words, n * sizeof *out->words);
    out->nwords = n;
    out->entry_point = c->entry_point;
    if (c->opt && c->opt->want_listing) {
        if (c->listing.failed)
            return -1;
        out->listing = c->listing.data ? c->listing.data : calloc(1, 1);
        c->listing.data = NULL;
        if (!out->listing)
            return -1;
    }
    if (c->opt && c->opt->want_source_listing) {
        struct asm_buf b = {0};
        asm_source_listing(c, &b);
        if (b.failed || !b.data) {
            asm_buf_free(&b);
            return -1;
        }
        out->source_listing = b.data;
    }
    if (c->opt && c->opt->want_debug_file) {
        struct asm_buf b = {0};
        asm_debug_file(c, &b);
        if (b.failed || !b.data) {
            asm_buf_free(&b);
            return -1;
        }
        out->debug_file = (unsigned char *)b.data;
        out->debug_file_len = b.len;
    }
    return 0;
}

static int assemble(const struct pruasm_options *opt, const char *path, const char *text,
                    struct pruasm_image *out, struct pruasm_diag *diag) {
    memset(out, 0, sizeof *out);
    struct pruasm_diag dummy = {0};
    if (!diag)
        diag = &dummy;
    diag->errors = diag->warnings = 0;
    diag->first_error[0] = 0;
    diag->pass = 0;

    struct asm_ctx *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(diag->first_error, sizeof diag->first_error, "Error: out of memory");
        diag->errors = 1;
        return -1;
    }
    c->opt = opt;
    c->diag = diag;
    c->core = opt && opt->core ? opt->core : CORE_V3;
    c->main_path = path;
    c->main_text = text;
    c->retreg = 30;
    c->retfield = PRU_SEL_W0;
    if (c->core < CORE_V1 || c->core > CORE_V3) {
        asm_report(c, NULL, REP_ERROR, "Core version V%d is not supported", c->core);
        release(c);
        return -1;
    }

    int pass1_offset = 0;
    for (c->pass = 1; c->pass <= 2 && !c->errors; c->pass++) {
        diag->pass = c->pass;
        run_pass(c);
        if (c->pass == 1)
            pass1_offset = c->code_offset;
    }
    c->pass = diag->pass;
    if (pass1_offset != c->code_offset)
        asm_report_plain_error(c, "Error: Offset changed between pass 1 and pass 2");

    int rc = -1;
    if (!c->errors && c->code_offset > 0) {
        rc = fill_image(c, out);
        if (rc) {
            pruasm_image_free(out);
            asm_report(c, NULL, REP_ERROR, "Memory allocation failed");
        }
    } else if (!c->errors) {
        snprintf(diag->first_error, sizeof diag->first_error, "No code generated");
    }
    diag->errors = c->errors;
    diag->warnings = c->warnings;
    release(c);
    return rc;
}

int pruasm_assemble_file(const struct pruasm_options *opt, const char *path,
                         struct pruasm_image *out, struct pruasm_diag *diag) {
    return assemble(opt, path, NULL, out, diag);
}

int pruasm_assemble_string(const struct pruasm_options *opt, const char *name, const char *text,
                           struct pruasm_image *out, struct pruasm_diag *diag) {
    return assemble(opt, name && *name ? name : "string.p", text ? text : "", out, diag);
}

void pruasm_image_free(struct pruasm_image *img) {
    free(img->words);
    free(img->listing);
    free(img->source_listing);
    free(img->debug_file);
    memset(img, 0, sizeof *img);
}

/* Output formats, byte for byte as pasm writes them. */

static char *finish(struct asm_buf *b, size_t *len) {
    if (b->failed || !b->data) {
        asm_buf_free(b);
        return NULL;
    }
    if (len)
        *len = b->len;
    return b->data;
}

char *pruasm_format_c_array(const struct pruasm_image *img, const char *array_name, size_t *len) {
    struct asm_buf b = {0};
    asm_buf_printf(&b,
                   "\n\n/* This file contains the PRU instructions in a C array which are to  */\n"
                   "/* be downloaded from the host CPU to the PRU instruction memory.     */\n"
                   "/* This file is generated by the PRU assembler.                       */\n");
    asm_buf_printf(&b, "\nconst unsigned int %s[] =  {\n", array_name ? array_name : "PRUcode");
    for (size_t i = 0; i + 1 < img->nwords; i++)
        asm_buf_printf(&b, "     0x%08x,\n", (unsigned)img->words[i]);
    asm_buf_printf(&b, "     0x%08x };\n\n",
                   (unsigned)(img->nwords ? img->words[img->nwords - 1] : 0));
    return finish(&b, len);
}

char *pruasm_format_fb_array(const struct pruasm_image *img, const char *array_name, size_t *len) {
    struct asm_buf b = {0};
    asm_buf_printf(&b, "\n\n' This file contains the PRU instructions in a FB array which are  \n"
                       "' to be downloaded from the host CPU to the PRU instruction memory.\n"
                       "' This file is generated by the PRU assembler.                     \n");
    asm_buf_printf(&b, "\nSTATIC SHARED AS UINTEGER %s(...) = { _\n",
                   array_name ? array_name : "PRUcode");
    for (size_t i = 0; i + 1 < img->nwords; i++)
        asm_buf_printf(&b, "  &H%08x, _\n", (unsigned)img->words[i]);
    asm_buf_printf(&b, "  &H%08x }\n\n", (unsigned)(img->nwords ? img->words[img->nwords - 1] : 0));
    return finish(&b, len);
}

char *pruasm_format_img(const struct pruasm_image *img, size_t *len) {
    struct asm_buf b = {0};
    for (size_t i = 0; i < img->nwords; i++)
        asm_buf_printf(&b, "%08x\n", (unsigned)img->words[i]);
    if (!img->nwords)
        asm_buf_put(&b, "", 0);
    return finish(&b, len);
}

unsigned char *pruasm_format_bin(const struct pruasm_image *img, int big_endian, size_t *len) {
    unsigned char *p = malloc(img->nwords * 4 + 1);
    if (!p)
        return NULL;
    for (size_t i = 0; i < img->nwords; i++) {
        uint32_t w = img->words[i];
        for (int k = 0; k < 4; k++)
            p[4 * i + (size_t)k] = (unsigned char)(w >> (8 * (big_endian ? 3 - k : k)));
    }
    if (len)
        *len = img->nwords * 4;
    return p;
}
