/* SHA-256 (FIPS 180-4), for the content hashes of manifests and resume.
 *
 * Function index
 *   dfl_sha256_init, _update, _final   streaming digest
 *   dfl_sha256_hex                     digest of a buffer as 64 hex digits
 *   dfl_sha256_file                    digest of a file's bytes as hex
 *
 * No library that dflab links (inih, Ceres, OpenEXR, zlib) exposes SHA-256,
 * and the function is short; tests/core/test_sha256.c checks the standard's
 * test vectors.
 */
#ifndef DFL_CORE_SHA256_H
#define DFL_CORE_SHA256_H

#include <stddef.h>
#include <stdint.h>

#include "core/status.h"

typedef struct dfl_sha256 {
    uint32_t h[8];
    uint64_t len;          /* bytes hashed so far */
    unsigned char buf[64]; /* partial block */
    size_t nbuf;
} dfl_sha256;

void dfl_sha256_init(dfl_sha256 *s);
void dfl_sha256_update(dfl_sha256 *s, const void *data, size_t n);
/* Writes the 32-byte digest; s must be re-initialized before reuse. */
void dfl_sha256_final(dfl_sha256 *s, unsigned char out[32]);
/* 64 lowercase hex digits and a NUL into hex (65 bytes). */
void dfl_sha256_hex(const void *data, size_t n, char hex[65]);
/* Digest of the file at path into hex; DFL_E_IO naming the path when it
 * cannot be read (hex is "" then). */
dfl_status dfl_sha256_file(const char *path, char hex[65], dfl_err *err);

#endif
