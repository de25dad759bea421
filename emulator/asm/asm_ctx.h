/*
 * asm_ctx.h - internal state of one pruasm assembly, shared by its modules.
 *
 * The limits below are pasm 0.87's (see docs/pru-facts.md §2); they
 * are kept because they decide which sources pasm accepts, and they double as
 * the bounds that keep malformed input from exhausting memory or stack.
 */
#ifndef ASM_CTX_H
#define ASM_CTX_H

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include "pruasm.h"
#include "asm_symtab.h"

#define ASM_TOKEN_MAX       128         /* names and operand terms are shorter than this */
#define ASM_MAX_TERMS       12          /* mnemonic + at most 11 operands */
#define ASM_LINE_MAX        8192        /* a statement after #define expansion */
#define ASM_RAW_LINE_MAX    16384       /* a source line after comment removal */
#define ASM_MACRO_LINE_MAX  256         /* a stored or expanded macro line */
#define ASM_MAX_WORDS       16384       /* program size */
#define ASM_MAX_OPEN        15          /* simultaneously open (nested) source files */
#define ASM_MAX_FILES       64          /* distinct source files */
#define ASM_MAX_ERRORS      25          /* give up after this many */
#define ASM_CC_MAX          8           /* #ifdef nesting */
#define ASM_NAME_MAX        64          /* source file base name */
#define ASM_DIR_MAX         256         /* source file directory */
#define ASM_FILE_MAX        (16u << 20) /* refuse larger source files */
#define ASM_MACRO_NEST_MAX  256         /* macro-in-macro depth (bounds the stack) */
#define ASM_EQUATE_NEST_MAX 1024        /* #define-in-#define depth */

enum asm_rep { REP_NOTE, REP_WARN1, REP_WARN2, REP_ERROR, REP_FATAL };

/* pasm's core versions (-V). */
enum { CORE_V1 = 1, CORE_V2 = 2, CORE_V3 = 3 };

/* A source file: its whole text is read once and kept for the -L listing. */
struct asm_file {
    char name[ASM_NAME_MAX]; /* base name, used in messages */
    char dir[ASM_DIR_MAX];   /* directory, for #include "..." */
    char *text;
    size_t len, pos;
    unsigned line; /* current line number */
    int last;      /* last character read (line counting) */
    int in_use;
    unsigned index;       /* position in asm_ctx.files */
    unsigned cc_depth_in; /* #ifdef depth when the file was opened */
};

/* Where a code word came from (for the listings). */
struct asm_wordinfo {
    uint32_t line;
    uint16_t file;
    uint8_t written;
};

/* A growing text buffer. */
struct asm_buf {
    char *data;
    size_t len, cap;
    int failed; /* out of memory: the text is incomplete */
};

struct asm_scope;
struct asm_struct;

struct asm_ctx {
    const struct pruasm_options *opt;
    struct pruasm_diag *diag;
    int core;
    int big_endian;        /* -E: register-file bytes are numbered from the MSB */
    const char *main_path; /* NULL when assembling a string */
    const char *main_text; /* the string being assembled */

    int pass;
    int code_offset; /* -1 until .origin or the first label/instruction */
    int entry_point;
    int have_entry;
    int errors, warnings, fatal;
    unsigned retreg, retfield;
    int retreg_set;

    uint32_t words[ASM_MAX_WORDS];
    struct asm_wordinfo info[ASM_MAX_WORDS];

    struct asm_file files[ASM_MAX_FILES];
    unsigned nfiles;
    int open_files;

    unsigned cc_depth;
    uint8_t cc_flags[ASM_CC_MAX];

    struct asm_symtab labels; /* value: (intptr_t) word address */
    char **label_order;       /* label names in creation order (for -d) */
    size_t nlabels, label_cap;
    struct asm_symtab equates; /* value: struct asm_equate * */
    struct asm_symtab macros;  /* value: struct asm_macro * */
    int macro_id;
    int macro_nest;  /* current macro expansion depth */
    int equate_nest; /* current equate expansion depth */

    struct asm_symtab structs; /* value: struct asm_struct * */
    struct asm_struct *struct_open;
    struct asm_scope *scopes; /* newest first */
    struct asm_scope *scope_cur;

    struct asm_buf listing;
};

/* asm_report.c */
void asm_report(struct asm_ctx *c, const struct asm_file *f, enum asm_rep level, const char *fmt,
                ...) __attribute__((format(printf, 4, 5)));
void asm_report_at(struct asm_ctx *c, const char *name, unsigned line, enum asm_rep level,
                   const char *fmt, ...) __attribute__((format(printf, 5, 6)));
void asm_report_abort(struct asm_ctx *c);
/* An error printed as a bare line (no location, no extra blank line). */
void asm_report_plain_error(struct asm_ctx *c, const char *text);
void asm_buf_printf(struct asm_buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void asm_buf_put(struct asm_buf *b, const char *s, size_t n);
void asm_buf_free(struct asm_buf *b);

/* asm_source.c: files, comments, # directives */
struct asm_file *asm_file_open(struct asm_ctx *c, struct asm_file *parent, const char *path,
                               int search_include_dirs);
void asm_file_close(struct asm_ctx *c, struct asm_file *f);
/* Next statement (directives handled, equates expanded) into dst.
 * Returns its length, 0 at end of file, -1 after an error on that line. */
int asm_get_line(struct asm_ctx *c, struct asm_file *f, char *dst, int max);
int asm_process_file(struct asm_ctx *c, struct asm_file *f);

/* asm_equate.c */
int asm_equate_create(struct asm_ctx *c, const struct asm_file *f, const char *name,
                      const char *value);
void asm_equate_define(struct asm_ctx *c, const struct asm_file *f, const char *src);
void asm_equate_undef(struct asm_ctx *c, const struct asm_file *f, const char *src);
int asm_equate_defined(struct asm_ctx *c, const char *name);
int asm_equate_expand(struct asm_ctx *c, const struct asm_file *f, const char *src, char *dst,
                      int *idx, int max);
void asm_equate_clear(struct asm_ctx *c);

/* asm_expr.c: returns 0 and the value, or -1 */
int asm_expr(struct asm_ctx *c, const struct asm_file *f, const char *s, uint32_t *out);
int asm_reg_offset(struct asm_ctx *c, const char *s, uint32_t *out);

/* asm_line.c */
struct asm_stmt {
    int has_label;
    int dot; /* first term starts with '.' */
    int nterms;
    char label[ASM_TOKEN_MAX];
    char term[ASM_MAX_TERMS][ASM_TOKEN_MAX];
};
int asm_parse_stmt(struct asm_ctx *c, const struct asm_file *f, const char *src,
                   struct asm_stmt *st);
int asm_process_line(struct asm_ctx *c, struct asm_file *f, const char *src);
int asm_label_char(int ch, int first);
int asm_check_name(struct asm_ctx *c, const struct asm_file *f, const char *name);
int asm_validate_offset(struct asm_ctx *c, const struct asm_file *f);
void asm_gen(struct asm_ctx *c, const struct asm_file *f, int nterms, char terms[][ASM_TOKEN_MAX],
             uint32_t word);
int asm_label_find(struct asm_ctx *c, const char *name, uint32_t *value);

/* asm_token.c */
#define TOK_UNRESERVED  0
#define TOK_OPCODE      0x01
#define TOK_DIRECTIVE   0x02
#define TOK_REG_BASE    0x04
#define TOK_REG_ADDR    0x08
#define TOK_REG_PTR     0x10
#define TOK_REG_POSTINC 0x20
#define TOK_REG_PREDEC  0x40
unsigned asm_token_type(const char *word);
int asm_is_mnemonic(const char *word);

enum asm_argtype { ARG_REG = 1, ARG_IMM, ARG_R0BYTE, ARG_CONST, ARG_OFFSET, ARG_REGBIT };
struct asm_arg {
    enum asm_argtype type;
    uint32_t value; /* register number, immediate, byte index, Cn, offset */
    unsigned field; /* enum pru_sel */
    unsigned bit;   /* .tN */
};
int asm_get_reg(struct asm_ctx *c, const struct asm_file *f, int num, const char *src,
                struct asm_arg *a, int bit_ok, char term);
int asm_get_imm(struct asm_ctx *c, const struct asm_file *f, int num, const char *src,
                struct asm_arg *a, uint32_t lo, uint32_t hi);
int asm_get_const(struct asm_ctx *c, const struct asm_file *f, int num, const char *src,
                  struct asm_arg *a);
/* Register-file byte order: the first byte of a field within its register
 * (0..3), and the field selector of `size` bytes at byte `off`. Big-endian
 * cores (-E) number the bytes of a register from its most significant end. */
unsigned asm_field_start(const struct asm_ctx *c, unsigned field);
unsigned asm_field_at(const struct asm_ctx *c, unsigned off, unsigned size);
int asm_get_r0byte(struct asm_ctx *c, const struct asm_file *f, int num, const char *src,
                   struct asm_arg *a);

/* asm_insn.c */
int asm_instruction(struct asm_ctx *c, struct asm_file *f, int nterms, char terms[][ASM_TOKEN_MAX]);

/* asm_dot.c: returns <0 error, 0 done, >0 length of a new statement in out */
int asm_dot_command(struct asm_ctx *c, struct asm_file *f, int nterms, char terms[][ASM_TOKEN_MAX],
                    char *out, int max);
int asm_is_dot_command(const char *word);

/* asm_macro.c */
int asm_macro_define(struct asm_ctx *c, struct asm_file *f, const char *name);
int asm_macro_exists(struct asm_ctx *c, const char *name);
int asm_macro_expand(struct asm_ctx *c, struct asm_file *f, int nterms,
                     char terms[][ASM_TOKEN_MAX]);
void asm_macro_clear(struct asm_ctx *c);

/* asm_struct.c */
void asm_struct_init(struct asm_ctx *c);
void asm_struct_clear(struct asm_ctx *c);
int asm_struct_new(struct asm_ctx *c, const struct asm_file *f, const char *name);
int asm_struct_end(struct asm_ctx *c, const struct asm_file *f);
int asm_struct_add(struct asm_ctx *c, const struct asm_file *f, const char *name, unsigned size);
int asm_struct_assign(struct asm_ctx *c, const struct asm_file *f, const char *sname,
                      const char *rs, const char *re, const char *name);
int asm_struct_param(struct asm_ctx *c, const struct asm_file *f, int idx, char *term);
int asm_struct_exists(struct asm_ctx *c, const char *name);
int asm_scope_enter(struct asm_ctx *c, const struct asm_file *f, const char *name);
int asm_scope_leave(struct asm_ctx *c, const struct asm_file *f, const char *name);
int asm_scope_using(struct asm_ctx *c, const struct asm_file *f, const char *name);

/* asm_listing.c: the -L source listing */
void asm_source_listing(struct asm_ctx *c, struct asm_buf *out);

/* asm_dbg.c: the -d pView debug file */
void asm_debug_file(struct asm_ctx *c, struct asm_buf *out);

#endif
