/*
 * asm_symtab.c - open-addressing hash table with linear probing and
 * tombstone-free deletion (backward shift), so lookups stay O(1) even for
 * sources with thousands of labels.
 */
#include "asm_symtab.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static size_t hash(const char *s) {
    uint64_t h = 1469598103934665603ull; /* FNV-1a */
    while (*s) {
        h ^= (unsigned char)*s++;
        h *= 1099511628211ull;
    }
    return (size_t)h;
}

static struct asm_sym *find(const struct asm_symtab *t, const char *name) {
    if (!t->cap)
        return NULL;
    for (size_t i = hash(name) & (t->cap - 1);; i = (i + 1) & (t->cap - 1)) {
        struct asm_sym *s = &t->slots[i];
        if (!s->name)
            return NULL;
        if (!strcmp(s->name, name))
            return s;
    }
}

void *asm_sym_get(const struct asm_symtab *t, const char *name, int *found) {
    struct asm_sym *s = find(t, name);
    if (found)
        *found = s != NULL;
    return s ? s->value : NULL;
}

static void insert(struct asm_symtab *t, char *name, void *value) {
    size_t i = hash(name) & (t->cap - 1);
    while (t->slots[i].name)
        i = (i + 1) & (t->cap - 1);
    t->slots[i].name = name;
    t->slots[i].value = value;
    t->count++;
}

static int grow(struct asm_symtab *t) {
    size_t ncap = t->cap ? t->cap * 2 : 64;
    struct asm_sym *old = t->slots;
    size_t ocap = t->cap;
    t->slots = calloc(ncap, sizeof *t->slots);
    if (!t->slots) {
        t->slots = old;
        return -1;
    }
    t->cap = ncap;
    t->count = 0;
    for (size_t i = 0; i < ocap; i++)
        if (old[i].name)
            insert(t, old[i].name, old[i].value);
    free(old);
    return 0;
}

int asm_sym_put(struct asm_symtab *t, const char *name, void *value) {
    struct asm_sym *s = find(t, name);
    if (s) {
        s->value = value;
        return 0;
    }
    if ((t->count + 1) * 2 > t->cap && grow(t))
        return -1;
    char *copy = strdup(name);
    if (!copy)
        return -1;
    insert(t, copy, value);
    return 0;
}

void *asm_sym_del(struct asm_symtab *t, const char *name) {
    struct asm_sym *s = find(t, name);
    if (!s)
        return NULL;
    void *value = s->value;
    free(s->name);
    size_t i = (size_t)(s - t->slots);
    t->slots[i].name = NULL;
    t->count--;
    /* Re-insert the rest of the probe run so no lookup stops at the hole. */
    for (size_t j = (i + 1) & (t->cap - 1); t->slots[j].name; j = (j + 1) & (t->cap - 1)) {
        struct asm_sym moved = t->slots[j];
        t->slots[j].name = NULL;
        t->count--;
        insert(t, moved.name, moved.value);
    }
    return value;
}

void asm_sym_clear(struct asm_symtab *t, void (*fn)(void *value)) {
    for (size_t i = 0; i < t->cap; i++) {
        if (t->slots[i].name) {
            if (fn)
                fn(t->slots[i].value);
            free(t->slots[i].name);
        }
    }
    free(t->slots);
    t->slots = NULL;
    t->cap = t->count = 0;
}
