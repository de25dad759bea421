/* fw_listing.c - labels and source lines from a pruasm listing (see
 * fw_listing.h). A listing line is
 *   file(  line) : 0xADDR = Label      : NAME:
 *   file(  line) : 0xADDR = 0xWORD     :     text
 */
#include "fw_listing.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* _NAME_m_k_ (a macro's label, numbered per definition and expansion) to
 * NAME; 0 if the name is not of that form. */
static int macro_label_base(const char *name, char *base, size_t len) {
    size_t n = strlen(name);
    if (n < 6 || name[0] != '_' || name[n - 1] != '_')
        return 0;
    size_t i = n - 1; /* the trailing '_' */
    for (int field = 0; field < 2; field++) {
        size_t end = i;
        while (i > 0 && isdigit((unsigned char)name[i - 1]))
            i--;
        if (i == end || i == 0 || name[i - 1] != '_')
            return 0;
        i--;
    }
    if (i <= 1 || i - 1 >= len)
        return 0;
    memcpy(base, name + 1, i - 1);
    base[i - 1] = '\0';
    return 1;
}

static char *dup_text(const char *s) {
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s, n);
    return d;
}

static int add_label(struct fw_listing *l, const char *name, uint32_t pc, size_t *cap) {
    if (l->nlabels == *cap) {
        size_t ncap = *cap ? 2 * *cap : 256;
        struct fw_label *p = realloc(l->labels, ncap * sizeof(*p));
        if (!p)
            return -1;
        l->labels = p;
        *cap = ncap;
    }
    struct fw_label *lb = &l->labels[l->nlabels++];
    snprintf(lb->name, sizeof(lb->name), "%s", name);
    lb->pc = pc;
    lb->in_macro = macro_label_base(name, lb->base, sizeof(lb->base));
    if (!lb->in_macro)
        snprintf(lb->base, sizeof(lb->base), "%s", name);
    return 0;
}

int fw_listing_parse(struct fw_listing *l, const char *listing, size_t nwords, const char *src_dir,
                     const char *main_text, char *err, size_t errlen) {
    memset(l, 0, sizeof(*l));
    l->src_dir = dup_text(src_dir ? src_dir : ".");
    l->main_text = main_text ? dup_text(main_text) : NULL;
    l->nwords = nwords;
    l->line = calloc(nwords ? nwords : 1, sizeof(*l->line));
    l->file = calloc(nwords ? nwords : 1, sizeof(*l->file));
    size_t cap = 0;
    if (!l->line || !l->file || !l->src_dir || (main_text && !l->main_text)) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    unsigned lineno = 0;
    for (const char *p = listing; *p; lineno++) {
        const char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p) : strlen(p);
        char row[512];
        snprintf(row, sizeof(row), "%.*s", (int)(n < sizeof(row) - 1 ? n : sizeof(row) - 1), p);
        p += n + (eol ? 1 : 0);
        char file[32], what[32];
        unsigned src_line, addr;
        int used = 0;
        if (sscanf(row, "%31[^(](%u) : 0x%x = %31s :%n", file, &src_line, &addr, what, &used) < 4 ||
            used == 0)
            continue; /* not a code or label row (a blank or message line) */
        if (strcmp(what, "Label") == 0) {
            char name[64];
            if (sscanf(row + used, " %63[^: ]", name) != 1) {
                snprintf(err, errlen, "listing line %u: a label without a name", lineno + 1);
                return -1;
            }
            if (add_label(l, name, addr, &cap) != 0) {
                snprintf(err, errlen, "out of memory");
                return -1;
            }
        } else if (addr < nwords) {
            if (!l->main_name[0])
                snprintf(l->main_name, sizeof(l->main_name), "%s", file);
            l->line[addr] = src_line;
            snprintf(l->file[addr], sizeof(l->file[addr]), "%s", file);
        } else {
            snprintf(err, errlen, "listing line %u: address 0x%x past the image (%zu words)",
                     lineno + 1, addr, nwords);
            return -1;
        }
    }
    if (l->nlabels == 0) {
        snprintf(err, errlen, "the listing has no labels");
        return -1;
    }
    return 0;
}

void fw_listing_free(struct fw_listing *l) {
    free(l->labels);
    free(l->line);
    free(l->file);
    free(l->src_dir);
    free(l->main_text);
    memset(l, 0, sizeof(*l));
}

int32_t fw_label_pc(const struct fw_listing *l, const char *name) {
    for (size_t i = 0; i < l->nlabels; i++)
        if (!l->labels[i].in_macro && strcmp(l->labels[i].name, name) == 0)
            return (int32_t)l->labels[i].pc;
    return -1;
}

const struct fw_label *fw_label_at(const struct fw_listing *l, uint32_t pc) {
    const struct fw_label *any = NULL;
    for (size_t i = 0; i < l->nlabels; i++) {
        if (l->labels[i].pc != pc)
            continue;
        if (!l->labels[i].in_macro)
            return &l->labels[i];
        if (!any)
            any = &l->labels[i];
    }
    return any;
}

/* The text of line `line`, trimmed of spaces and comment, into buf. */
static void trim_line(const char *text, size_t n, char *buf, size_t len) {
    while (n > 0 && isspace((unsigned char)*text)) {
        text++;
        n--;
    }
    for (size_t i = 0; i + 1 < n; i++)
        if (text[i] == '/' && text[i + 1] == '/')
            n = i;
    while (n > 0 && isspace((unsigned char)text[n - 1]))
        n--;
    snprintf(buf, len, "%.*s", (int)n, text);
}

/* Line `line` of the file (the main text, or src_dir/file) into buf ("" if
 * there is none). */
static void source_text(const struct fw_listing *l, const char *file, unsigned line, char *buf,
                        size_t len) {
    buf[0] = '\0';
    if (l->main_text && strcmp(file, l->main_name) == 0) {
        const char *p = l->main_text;
        for (unsigned i = 1; i < line && p; i++) {
            p = strchr(p, '\n');
            p = p ? p + 1 : NULL;
        }
        if (p) {
            const char *eol = strchr(p, '\n');
            trim_line(p, eol ? (size_t)(eol - p) : strlen(p), buf, len);
        }
        return;
    }
    char path[1024];
    snprintf(path, sizeof(path), "%s/%s", l->src_dir, file);
    FILE *f = fopen(path, "r");
    if (!f)
        return;
    char text[512];
    for (unsigned i = 1; fgets(text, sizeof(text), f); i++) {
        if (i == line) {
            trim_line(text, strlen(text), buf, len);
            break;
        }
    }
    fclose(f);
}

void fw_describe_pc(const struct fw_listing *l, uint32_t pc, char *buf, size_t len) {
    const struct fw_label *outer = NULL, *inner = NULL;
    for (size_t i = 0; i < l->nlabels; i++) {
        const struct fw_label *lb = &l->labels[i];
        if (lb->pc > pc)
            continue;
        if (!lb->in_macro && (!outer || lb->pc >= outer->pc))
            outer = lb;
        if (lb->in_macro && (!inner || lb->pc >= inner->pc))
            inner = lb;
    }
    char where[256] = "";
    if (outer)
        snprintf(where, sizeof(where), "%s+%u", outer->name, pc - outer->pc);
    if (inner && (!outer || inner->pc >= outer->pc)) {
        size_t n = strlen(where);
        snprintf(where + n, sizeof(where) - n, " in %s+%u", inner->base, pc - inner->pc);
    }
    char text[256] = "";
    if (pc < l->nwords && l->line[pc]) {
        source_text(l, l->file[pc], l->line[pc], text, sizeof(text));
        snprintf(buf, len, "pc 0x%03x %s (%s:%u `%s`)", pc, where, l->file[pc], l->line[pc], text);
    } else {
        snprintf(buf, len, "pc 0x%03x %s", pc, where);
    }
}
