#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "core/sha256.h"

/* FIPS 180-4 examples (NIST CSRC "SHA256.pdf") and the empty message. */
Test(sha256, standard_vectors)
{
    char hex[65];
    dfl_sha256_hex("", 0, hex);
    cr_expect_str_eq(hex, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    dfl_sha256_hex("abc", 3, hex);
    cr_expect_str_eq(hex, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    const char *m = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
    dfl_sha256_hex(m, strlen(m), hex);
    cr_expect_str_eq(hex, "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

/* A million 'a' fed in uneven pieces (crosses every buffer boundary case). */
Test(sha256, streaming_in_pieces_and_files)
{
    static char a[1000000];
    memset(a, 'a', sizeof a);
    dfl_sha256 s;
    dfl_sha256_init(&s);
    size_t off = 0, k = 1;
    while (off < sizeof a) {
        size_t n = k < sizeof a - off ? k : sizeof a - off;
        dfl_sha256_update(&s, a + off, n);
        off += n;
        k = k * 3 % 97 + 1;
    }
    unsigned char d[32];
    dfl_sha256_final(&s, d);
    char hex[65];
    for (int i = 0; i < 32; i++) sprintf(hex + 2 * i, "%02x", d[i]);
    cr_expect_str_eq(hex, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");

    char path[] = "/tmp/dflab-sha-XXXXXX";
    int fd = mkstemp(path);
    cr_assert(fd >= 0);
    cr_assert_eq(write(fd, a, sizeof a), (ssize_t)sizeof a);
    close(fd);
    dfl_err err;
    cr_assert_eq(dfl_sha256_file(path, hex, &err), DFL_OK);
    cr_expect_str_eq(hex, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
    remove(path);
    cr_expect_eq(dfl_sha256_file(path, hex, &err), DFL_E_IO);
    cr_expect(strstr(err.msg, path) != NULL);
}

/* Padding puts 0x80 and the 8-byte bit length after the message: a tail of
 * up to 55 bytes fits its block, 56..63 bytes spill into a second one
 * (FIPS 180-4 5.1.1).  The lengths around both edges, message byte i =
 * 'a' + i % 26; the digests are those of an independent implementation
 * (Python's hashlib.sha256). */
Test(sha256, padding_edges)
{
    static const struct {
        size_t n;
        const char *hex;
    } v[] = {
        {55, "595615dbe4f0f407ae397d08b4c2cb870cb9b0e11937416f950c5160acf9c005"},
        {56, "784f623b787495078e93ff28a25b581df0584055a7e71d8cd90c454716b92f51"},
        {63, "5ca3e1ef5207490eac01a795e5cc94d59582a5118bf9534665c8668d87aa647c"},
        {64, "2fcd5a0d60e4c941381fcc4e00a4bf8be422c3ddfafb93c809e8d1e2bfffae8e"},
        {119, "faef67da856d6fd9c8d12f9ed0a4fefd3cf0ce085ab43e2907418d457e3c354b"},
        {120, "c9512b08619c19fbb503c7da6b46ef20301e5f7a7a5f43989182398536f5c5c8"},
    };
    char m[120], hex[65];
    for (size_t i = 0; i < sizeof m; i++) m[i] = (char)('a' + i % 26);
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) {
        dfl_sha256_hex(m, v[k].n, hex);
        cr_expect_str_eq(hex, v[k].hex, "%zu bytes", v[k].n);
    }
}
