/*
 * asm_symtab.h - a string-keyed hash table for the assembler's names
 * (labels, equates, macros, structures). Keys are copied; values are opaque.
 */
#ifndef ASM_SYMTAB_H
#define ASM_SYMTAB_H

#include <stddef.h>

struct asm_sym {
    char *name;
    void *value;
};

struct asm_symtab {
    struct asm_sym *slots;
    size_t cap, count;
};

/* The value of `name`, or NULL; *found says whether it exists. */
void *asm_sym_get(const struct asm_symtab *t, const char *name, int *found);
/* Add or replace. Returns 0, or -1 when out of memory. */
int asm_sym_put(struct asm_symtab *t, const char *name, void *value);
/* Remove `name`; returns its value (NULL if absent). */
void *asm_sym_del(struct asm_symtab *t, const char *name);
/* Call fn on every value, then empty the table. */
void asm_sym_clear(struct asm_symtab *t, void (*fn)(void *value));

#endif
