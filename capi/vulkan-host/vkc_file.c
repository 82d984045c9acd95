/* Reading a SPIR-V file. */
#include "vkc_internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int vkc_read_file(const char *path, uint32_t **words, size_t *bytes, char *err, size_t err_len) {
    FILE *f;
    unsigned char *data = NULL;
    size_t len = 0, cap = 0;

    if (err != NULL && err_len > 0) err[0] = '\0';
    if (words == NULL || bytes == NULL) {
        vkci_fail(err, err_len, "vkc_read_file: words or bytes is NULL");
        return 1;
    }
    *words = NULL;
    *bytes = 0;
    if (path == NULL) {
        vkci_fail(err, err_len, "vkc_read_file: path is NULL");
        return 1;
    }
    f = fopen(path, "rb");
    if (f == NULL) {
        vkci_fail(err, err_len, "cannot open %s: %s", path, strerror(errno));
        return 1;
    }
    /* Read in growing chunks rather than trusting fseek/ftell, which fail on
     * pipes and overflow long on 32-bit hosts. */
    for (;;) {
        size_t got;
        if (len == cap) {
            size_t next = cap == 0 ? 65536 : cap * 2;
            unsigned char *grown;
            if (next < cap) {
                vkci_fail(err, err_len, "%s is too large", path);
                goto fail;
            }
            grown = (unsigned char *)realloc(data, next);
            if (grown == NULL) {
                vkci_fail(err, err_len, "out of host memory reading %s", path);
                goto fail;
            }
            data = grown;
            cap = next;
        }
        got = fread(data + len, 1, cap - len, f);
        len += got;
        if (got == 0) break;
    }
    if (ferror(f)) {
        vkci_fail(err, err_len, "error reading %s", path);
        goto fail;
    }
    if (len == 0) {
        vkci_fail(err, err_len, "%s is empty", path);
        goto fail;
    }
    if (len % 4 != 0) {
        vkci_fail(err, err_len, "%s is %lu bytes, not a whole number of 32-bit SPIR-V words", path, (unsigned long)len);
        goto fail;
    }
    fclose(f);
    /* malloc'd memory is aligned for any object type, so the bytes may be
     * read as words. */
    *words = (uint32_t *)(void *)data;
    *bytes = len;
    return 0;
fail:
    fclose(f);
    free(data);
    return 1;
}
